//! Culling: only passes that contribute to an export, an import or a side effect run, and
//! everything dropped says why.

use crate::common;

use common::{clear_pass, plan, tex, CLEAR};
use rgraph_core::types::TextureFormat::Rgba8Unorm;
use rgraph_core::{ColorLoad, GraphBuilder, Plan};

fn culled(plan: &Plan) -> Vec<(&str, &str)> {
    plan.culled
        .iter()
        .map(|c| (c.name.as_str(), c.reason.as_str()))
        .collect()
}

fn live(plan: &Plan) -> Vec<&str> {
    plan.passes.iter().map(|p| p.name.as_str()).collect()
}

#[test]
fn a_pass_whose_output_nobody_reads_is_culled() {
    let mut g = GraphBuilder::new();
    let debug = g.create_texture("debug_view", tex(Rgba8Unorm));
    let out = g.create_texture("out", tex(Rgba8Unorm));
    g.add_render_pass("debug").color_output(debug, CLEAR);
    clear_pass(&mut g, "main", out);
    let plan = plan(&g.build());

    assert_eq!(live(&plan), ["main"]);
    assert_eq!(
        culled(&plan),
        [(
            "debug",
            r#"nothing reads "debug_view" and it is not an output"#
        )]
    );
}

#[test]
fn a_side_effect_pass_is_kept_with_what_it_reads() {
    let mut g = GraphBuilder::new();
    let t = g.create_texture("t", tex(Rgba8Unorm));
    let t = g.add_render_pass("draw").color_output(t, CLEAR);
    let mut readback = g.add_compute_pass("readback");
    readback.sampled(t);
    readback.side_effect();
    let plan = plan(&g.build());

    assert_eq!(live(&plan), ["draw", "readback"]);
    assert!(plan.culled.is_empty());
}

#[test]
fn a_pass_without_writes_or_side_effects_is_culled() {
    let mut g = GraphBuilder::new();
    let t = g.import_texture("t", tex(Rgba8Unorm));
    g.add_compute_pass("peek").sampled(t);
    assert_eq!(
        culled(&plan(&g.build())),
        [(
            "peek",
            "it writes nothing and is not marked as a side effect"
        )]
    );
}

#[test]
fn a_write_overwritten_before_anything_reads_it_is_culled() {
    let mut g = GraphBuilder::new();
    let t = g.create_texture("t", tex(Rgba8Unorm));
    let t = g.add_render_pass("stale").color_output(t, CLEAR);
    clear_pass(&mut g, "fresh", t);
    let plan = plan(&g.build());

    assert_eq!(live(&plan), ["fresh"]);
    assert_eq!(
        culled(&plan),
        [(
            "stale",
            r#""t" is overwritten by "fresh" before anything reads it"#
        )]
    );
}

/// A pass feeding only dead passes is dead too, and says which ones.
#[test]
fn a_pass_read_only_by_culled_passes_is_culled() {
    let mut g = GraphBuilder::new();
    let a = g.create_texture("a", tex(Rgba8Unorm));
    let b = g.create_texture("b", tex(Rgba8Unorm));
    let out = g.create_texture("out", tex(Rgba8Unorm));
    let a = g.add_render_pass("make_a").color_output(a, CLEAR);
    let mut p = g.add_render_pass("make_b");
    p.sampled(a);
    p.color_output(b, CLEAR);
    clear_pass(&mut g, "main", out);
    let plan = plan(&g.build());

    assert_eq!(
        culled(&plan),
        [
            ("make_a", r#""a" is read only by culled passes ("make_b")"#),
            ("make_b", r#"nothing reads "b" and it is not an output"#),
        ]
    );
}

/// Writing into an import is a result the engine sees, so the writer of its final version
/// runs with what it loads; an earlier writer cleared over does not.
#[test]
fn the_final_writer_of_an_import_is_kept() {
    let mut g = GraphBuilder::new();
    let swapchain = g.import_texture("swapchain", tex(Rgba8Unorm));
    let s1 = g.add_render_pass("splash").color_output(swapchain, CLEAR);
    let s2 = g.add_render_pass("scene").color_output(s1, CLEAR);
    g.add_render_pass("ui").color_output(s2, ColorLoad::Load);
    let plan = plan(&g.build());

    assert_eq!(live(&plan), ["scene", "ui"]);
    assert_eq!(plan.culled[0].name, "splash");
}

#[test]
fn resources_say_why_they_are_not_allocated() {
    let mut g = GraphBuilder::new();
    let dead = g.create_texture("dead_target", tex(Rgba8Unorm));
    g.create_texture("unused", tex(Rgba8Unorm));
    let out = g.create_texture("out", tex(Rgba8Unorm));
    g.add_render_pass("debug").color_output(dead, CLEAR);
    clear_pass(&mut g, "main", out);
    let plan = plan(&g.build());

    let reason = |name| plan.find(name).unwrap().culled.as_deref();
    assert_eq!(
        reason("dead_target"),
        Some(r#"used only by culled passes ("debug")"#)
    );
    assert_eq!(reason("unused"), Some("no pass uses it"));
    assert_eq!(reason("out"), None);
    let dead = plan.find("dead_target").unwrap();
    assert_eq!((dead.physical, dead.lifetime), (None, None));
}
