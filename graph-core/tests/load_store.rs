//! Load/store inference: clear on a fresh write, load to build on earlier contents, store
//! only what a later pass or the world outside reads.

use crate::common;

use common::{plan, tex, CLEAR};
use rgraph_core::types::TextureFormat::{Depth24PlusStencil8, Depth32Float, Rgba8Unorm};
use rgraph_core::{
    AspectAccess, ColorAttachment, ColorLoad, DepthStencilAttachment, GraphBuilder, Load, Ops,
    Plan, Store,
};

fn color(plan: &Plan, pass: &str) -> Vec<ColorAttachment> {
    plan.pass(pass).unwrap().color.clone()
}

fn ops(load: Load<[f64; 4]>, store: Store) -> Ops<[f64; 4]> {
    Ops { load, store }
}

#[test]
fn a_fresh_write_clears_and_a_modification_loads() {
    let mut g = GraphBuilder::new();
    let t = g.create_texture("t", tex(Rgba8Unorm));
    let sky = [0.1, 0.2, 0.3, 1.0];
    let t1 = g
        .add_render_pass("sky")
        .color_output(t, ColorLoad::Clear(sky));
    let t2 = g.add_render_pass("ui").color_output(t1, ColorLoad::Load);
    g.export(t2);
    let plan = plan(&g.build());
    let id = plan.find("t").unwrap().id;

    assert_eq!(
        color(&plan, "sky"),
        [ColorAttachment {
            resource: id,
            ops: ops(Load::Clear(sky), Store::Store),
            resolve_target: None,
        }]
    );
    assert_eq!(color(&plan, "ui")[0].ops, ops(Load::Load, Store::Store));
}

/// The multisampled target is resolved at the end of its pass and nothing reads it later:
/// its samples are discarded, and the resolve target alone carries the result.
#[test]
fn a_resolved_target_nothing_reads_again_is_discarded() {
    let mut g = GraphBuilder::new();
    let msaa = g.create_texture("msaa", tex(Rgba8Unorm).samples(4));
    let out = g.create_texture("out", tex(Rgba8Unorm));
    let mut p = g.add_render_pass("draw");
    let msaa = p.color_output(msaa, CLEAR);
    let out = p.resolve_output(msaa, out);
    g.export(out);
    let plan = plan(&g.build());

    assert_eq!(
        color(&plan, "draw"),
        [ColorAttachment {
            resource: plan.find("msaa").unwrap().id,
            ops: ops(Load::Clear([0.0; 4]), Store::Discard),
            resolve_target: Some(plan.find("out").unwrap().id),
        }]
    );
}

/// A read by a culled pass does not count: that pass never runs.
#[test]
fn a_target_read_only_by_a_culled_pass_is_discarded() {
    let mut g = GraphBuilder::new();
    let [t, out, debug] = ["t", "out", "debug"].map(|n| g.create_texture(n, tex(Rgba8Unorm)));
    let mut p = g.add_render_pass("draw");
    let t = p.color_output(t, CLEAR);
    let out = p.color_output(out, CLEAR);
    g.export(out);
    let mut p = g.add_render_pass("debug");
    p.sampled(t);
    p.color_output(debug, CLEAR);
    let plan = plan(&g.build());

    let stores: Vec<Store> = color(&plan, "draw").iter().map(|c| c.ops.store).collect();
    assert_eq!(stores, [Store::Discard, Store::Store]);
}

/// An import's final version is the engine's result; earlier versions are stored only
/// when a later pass reads them.
#[test]
fn the_final_version_of_an_import_is_stored() {
    let mut g = GraphBuilder::new();
    let swapchain = g.import_texture("swapchain", tex(Rgba8Unorm));
    let s1 = g.add_render_pass("scene").color_output(swapchain, CLEAR);
    g.add_render_pass("ui").color_output(s1, ColorLoad::Load);
    let plan = plan(&g.build());

    assert_eq!(color(&plan, "scene")[0].ops.store, Store::Store);
    assert_eq!(color(&plan, "ui")[0].ops, ops(Load::Load, Store::Store));
}

#[test]
fn read_only_aspects_have_no_ops() {
    let mut g = GraphBuilder::new();
    let depth = g.create_texture("depth", tex(Depth24PlusStencil8));
    let out = g.create_texture("out", tex(Rgba8Unorm));
    let depth = g.add_render_pass("prepass").depth_stencil(
        depth,
        AspectAccess::Clear(1.0),
        AspectAccess::Clear(0),
    );
    let mut p = g.add_render_pass("mark");
    let out = p.color_output(out, CLEAR);
    p.depth_stencil(depth, AspectAccess::ReadOnly, AspectAccess::Load);
    g.export(out);
    let plan = plan(&g.build());

    let depth = plan.find("depth").unwrap().id;
    assert_eq!(
        plan.pass("prepass").unwrap().depth_stencil,
        Some(DepthStencilAttachment {
            resource: depth,
            depth: Some(Ops {
                load: Load::Clear(1.0),
                store: Store::Store,
            }),
            stencil: Some(Ops {
                load: Load::Clear(0),
                store: Store::Store,
            }),
        })
    );
    assert_eq!(
        plan.pass("mark").unwrap().depth_stencil,
        Some(DepthStencilAttachment {
            resource: depth,
            depth: None,
            stencil: Some(Ops {
                load: Load::Load,
                store: Store::Discard,
            }),
        })
    );
}

#[test]
fn a_depth_only_format_has_no_stencil_ops() {
    let mut g = GraphBuilder::new();
    let depth = g.create_texture("depth", tex(Depth32Float));
    let depth = g.add_render_pass("prepass").depth_stencil(
        depth,
        AspectAccess::Clear(1.0),
        AspectAccess::ReadOnly,
    );
    g.export(depth);
    let plan = plan(&g.build());

    let ds = plan.pass("prepass").unwrap().depth_stencil.clone().unwrap();
    assert_eq!(
        (ds.depth, ds.stencil),
        (
            Some(Ops {
                load: Load::Clear(1.0),
                store: Store::Store
            }),
            None
        )
    );
}

/// An overwrite begins the resource as a clear does (it needs no earlier writer), and the
/// plan says the device neither clears nor reads: what the pass leaves undrawn is
/// undefined, which explain states.
#[test]
fn an_overwrite_begins_a_texture_without_clearing_it() {
    let mut g = GraphBuilder::new();
    let depth = g.create_texture("depth", tex(Depth32Float));
    let out = g.create_texture("out", tex(Rgba8Unorm));
    let depth = g.add_render_pass("keys").depth_stencil(
        depth,
        AspectAccess::Overwrite,
        AspectAccess::Absent,
    );
    let mut p = g.add_render_pass("test against it");
    let out = p.color_output(out, CLEAR);
    p.depth_stencil(depth, AspectAccess::ReadOnly, AspectAccess::Absent);
    g.export(out);
    let plan = plan(&g.build());

    let ds = plan.pass("keys").unwrap().depth_stencil.clone().unwrap();
    assert_eq!(
        ds.depth,
        Some(Ops {
            load: Load::Overwrite,
            store: Store::Store,
        })
    );
    let explained = rgraph_core::explain::text(&plan);
    assert!(
        explained.contains("depth-stencil: depth depth overwrite (not cleared) -> store"),
        "{explained}"
    );
}

/// A color target a full-screen pass draws whole is overwritten, not cleared, as a depth
/// aspect is, and reads nothing: the pass before it that wrote the texture is culled.
#[test]
fn a_color_overwrite_neither_clears_nor_reads() {
    let mut g = GraphBuilder::new();
    let target = g.create_texture("target", tex(Rgba8Unorm));
    let cleared = g.add_render_pass("earlier").color_output(target, CLEAR);
    let drawn = g
        .add_render_pass("full screen")
        .color_output(cleared, ColorLoad::Overwrite);
    g.export(drawn);
    let plan = plan(&g.build());

    assert_eq!(
        color(&plan, "full screen")[0].ops,
        ops(Load::Overwrite, Store::Store)
    );
    assert!(plan.pass("earlier").is_none(), "{:?}", plan.passes);
}
