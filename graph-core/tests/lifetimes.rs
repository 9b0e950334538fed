//! Lifetimes: the span of execution positions over which each resource must exist.

use crate::common;

use common::{plan, tex, CLEAR};
use rgraph_core::types::TextureFormat::Rgba8Unorm;
use rgraph_core::{ColorLoad, GraphBuilder};

#[test]
fn a_resource_lives_from_its_first_to_its_last_use() {
    let mut g = GraphBuilder::new();
    let [a, b, out] = ["a", "b", "out"].map(|n| g.create_texture(n, tex(Rgba8Unorm)));
    let a = g.add_render_pass("p0").color_output(a, CLEAR);
    let mut p = g.add_render_pass("p1");
    p.sampled(a);
    let b = p.color_output(b, CLEAR);
    let mut p = g.add_render_pass("p2");
    p.sampled(a);
    p.sampled(b);
    let out = p.color_output(out, CLEAR);
    g.export(out);
    let plan = plan(&g.build());

    let lifetime = |name| plan.find(name).unwrap().lifetime;
    assert_eq!(lifetime("a"), Some((0, 2)));
    assert_eq!(lifetime("b"), Some((1, 2)));
    assert_eq!(lifetime("out"), Some((2, 2)));
}

/// An export outlives the frame, so it lives to the last pass whatever its last use.
#[test]
fn an_export_lives_to_the_end() {
    let mut g = GraphBuilder::new();
    let [history, t] = ["history", "t"].map(|n| g.create_texture(n, tex(Rgba8Unorm)));
    let history = g.add_render_pass("history").color_output(history, CLEAR);
    g.export(history);
    let t = g.add_render_pass("p1").color_output(t, CLEAR);
    let t = g.add_render_pass("p2").color_output(t, ColorLoad::Load);
    g.export(t);
    let plan = plan(&g.build());

    assert_eq!(plan.find("history").unwrap().lifetime, Some((0, 2)));
}

/// Positions are in execution order: "late" was declared last but runs second.
#[test]
fn lifetimes_follow_the_execution_order() {
    let mut g = GraphBuilder::new();
    let [hdr, late] = ["hdr", "late"].map(|n| g.create_texture(n, tex(Rgba8Unorm)));
    let lit = g.add_render_pass("light").color_output(hdr, CLEAR);
    let mapped = g.add_render_pass("map").color_output(lit, ColorLoad::Load);
    g.export(mapped);
    let mut p = g.add_render_pass("late");
    p.sampled(lit);
    let late = p.color_output(late, CLEAR);
    g.export(late);
    let plan = plan(&g.build());

    assert_eq!(plan.find("late").unwrap().lifetime, Some((1, 2)));
    assert_eq!(plan.find("hdr").unwrap().lifetime, Some((0, 2)));
}
