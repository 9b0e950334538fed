//! Ordering: live passes run after the producers of what they read, before the writers of
//! what they read over, in declaration order otherwise; a graph that allows no such order
//! is a cycle, reported with its passes.

use crate::common;

use common::{clear_pass, errors, plan, tex, CLEAR};
use rgraph_core::types::TextureFormat::Rgba8Unorm;
use rgraph_core::{ColorLoad, GraphBuilder, GraphError, Plan};

fn names(plan: &Plan) -> Vec<&str> {
    plan.passes.iter().map(|p| p.name.as_str()).collect()
}

#[test]
fn independent_passes_run_in_declaration_order() {
    let mut g = GraphBuilder::new();
    for name in ["c", "a", "b"] {
        let t = g.create_texture(name, tex(Rgba8Unorm));
        clear_pass(&mut g, name, t);
    }
    assert_eq!(names(&plan(&g.build())), ["c", "a", "b"]);
}

/// "bloom" reads the first version of "hdr", which "tonemap" writes over: it must run
/// first even though it was declared later.
#[test]
fn a_reader_of_an_old_version_runs_before_the_pass_that_overwrites_it() {
    let mut g = GraphBuilder::new();
    let hdr = g.create_texture("hdr", tex(Rgba8Unorm));
    let bloom = g.create_texture("bloom", tex(Rgba8Unorm));
    let lit = g.add_render_pass("lighting").color_output(hdr, CLEAR);
    let mut tonemap = g.add_render_pass("tonemap");
    let mapped = tonemap.color_output(lit, ColorLoad::Load);
    g.export(mapped);
    let mut p = g.add_render_pass("bloom");
    p.sampled(lit);
    let bloom = p.color_output(bloom, CLEAR);
    g.export(bloom);

    assert_eq!(names(&plan(&g.build())), ["lighting", "bloom", "tonemap"]);
}

/// "clear_again" writes over the version a culled pass produced. It still writes the
/// memory "late_reader" reads the first version from, so it must wait for that reader.
#[test]
fn a_write_after_a_culled_write_still_waits_for_readers_of_the_older_version() {
    let mut g = GraphBuilder::new();
    let t = g.create_texture("t", tex(Rgba8Unorm));
    let out = g.create_texture("out", tex(Rgba8Unorm));
    let first = g.add_render_pass("first").color_output(t, CLEAR);
    let dead = g.add_render_pass("dead").color_output(first, CLEAR);
    clear_pass(&mut g, "clear_again", dead);
    let mut p = g.add_render_pass("late_reader");
    p.sampled(first);
    let out = p.color_output(out, CLEAR);
    g.export(out);

    let plan = plan(&g.build());
    assert_eq!(names(&plan), ["first", "late_reader", "clear_again"]);
    assert_eq!(plan.culled[0].name, "dead");
}

#[test]
fn the_order_is_the_same_on_every_compile() {
    let mut g = GraphBuilder::new();
    let a = g.create_texture("a", tex(Rgba8Unorm));
    let b = g.create_texture("b", tex(Rgba8Unorm));
    let a = g.add_render_pass("a").color_output(a, CLEAR);
    let b = g.add_render_pass("b").color_output(b, CLEAR);
    for name in ["x", "y", "z"] {
        let out = g.create_texture(name, tex(Rgba8Unorm));
        let mut p = g.add_render_pass(name);
        p.sampled(a);
        p.sampled(b);
        let out = p.color_output(out, CLEAR);
        g.export(out);
    }
    let graph = g.build();
    let first = names(&plan(&graph)).join(" ");
    for _ in 0..10 {
        assert_eq!(names(&plan(&graph)).join(" "), first);
    }
    assert_eq!(first, "a b x y z");
}

/// "combine" reads "r" before "update" writes over it (so it must run first) and "s" after
/// "update" writes it (so it must run after): no order satisfies both.
#[test]
fn reading_an_old_and_a_new_output_of_one_pass_is_a_cycle() {
    let mut g = GraphBuilder::new();
    let r = g.create_texture("r", tex(Rgba8Unorm));
    let s = g.create_texture("s", tex(Rgba8Unorm));
    let out = g.create_texture("out", tex(Rgba8Unorm));
    let r1 = g.add_render_pass("init").color_output(r, CLEAR);
    let mut update = g.add_render_pass("update");
    let s1 = update.color_output(s, CLEAR);
    let r2 = update.color_output(r1, ColorLoad::Load);
    g.export(r2);
    let mut combine = g.add_render_pass("combine");
    combine.sampled(r1);
    combine.sampled(s1);
    let out = combine.color_output(out, CLEAR);
    g.export(out);

    let errors = errors(&g.build());
    assert_eq!(
        errors,
        [GraphError::Cycle {
            passes: vec!["update".into(), "combine".into()],
            resources: vec!["r".into(), "s".into()],
        }]
    );
    assert_eq!(
        errors[0].to_string(),
        r#"cycle: passes "update", "combine" must each run before the other (through "r", "s")"#
    );
}
