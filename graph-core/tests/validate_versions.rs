//! Version errors found while declaring: data read before anything wrote it, two writers
//! of one version, handles from another graph.

use crate::common;

use common::{clear_pass, only_error, plan, tex, CLEAR};
use rgraph_core::types::TextureFormat::{Rgba16Float, Rgba8Unorm};
use rgraph_core::{ColorLoad, GraphBuilder, GraphError};

#[test]
fn sampling_a_transient_nothing_wrote_names_pass_and_resource() {
    let mut g = GraphBuilder::new();
    let normal = g.create_texture("gbuffer.normal", tex(Rgba16Float));
    let hdr = g.create_texture("hdr", tex(Rgba16Float));
    let mut light = g.add_render_pass("light");
    light.sampled(normal);
    let lit = light.color_output(hdr, CLEAR);
    g.export(lit);

    let error = only_error(&g.build());
    assert_eq!(
        error,
        GraphError::ReadBeforeWrite {
            pass: "light".into(),
            resource: "gbuffer.normal".into(),
        }
    );
    assert_eq!(
        error.to_string(),
        r#"pass "light" reads "gbuffer.normal", which no pass writes"#
    );
}

#[test]
fn loading_a_fresh_transient_is_a_read_before_write() {
    let mut g = GraphBuilder::new();
    let t = g.create_texture("accum", tex(Rgba8Unorm));
    let out = g.add_render_pass("blend").color_output(t, ColorLoad::Load);
    g.export(out);

    assert_eq!(
        only_error(&g.build()),
        GraphError::ReadBeforeWrite {
            pass: "blend".into(),
            resource: "accum".into(),
        }
    );
}

/// Validation does not depend on culling: a graph file with a broken branch is broken even
/// when nothing needs that branch today.
#[test]
fn a_read_before_write_in_a_culled_branch_is_still_reported() {
    let mut g = GraphBuilder::new();
    let unwritten = g.create_texture("unwritten", tex(Rgba8Unorm));
    let scratch = g.create_texture("scratch", tex(Rgba8Unorm));
    let out = g.create_texture("out", tex(Rgba8Unorm));
    let mut dead = g.add_render_pass("dead");
    dead.sampled(unwritten);
    dead.color_output(scratch, CLEAR);
    clear_pass(&mut g, "live", out);

    assert_eq!(only_error(&g.build()).pass(), Some("dead"));
}

#[test]
fn reading_version_zero_of_an_import_is_allowed() {
    let mut g = GraphBuilder::new();
    let history = g.import_texture("history", tex(Rgba8Unorm));
    let out = g.create_texture("out", tex(Rgba8Unorm));
    let mut taa = g.add_render_pass("taa");
    taa.sampled(history);
    let out = taa.color_output(out, CLEAR);
    g.export(out);

    assert_eq!(plan(&g.build()).passes.len(), 1);
}

#[test]
fn two_passes_writing_through_one_handle_are_named_both() {
    let mut g = GraphBuilder::new();
    let t = g.create_texture("shadow", tex(Rgba8Unorm));
    clear_pass(&mut g, "cascade0", t);
    clear_pass(&mut g, "cascade1", t);

    let error = only_error(&g.build());
    assert_eq!(
        error,
        GraphError::ConflictingWriters {
            first: "cascade0".into(),
            second: "cascade1".into(),
            resource: "shadow".into(),
            version: 0,
        }
    );
    assert_eq!(
        error.to_string(),
        r#"passes "cascade0" and "cascade1" both write over version 0 of "shadow"; a version has one writer (write through the handle "cascade0" returned)"#
    );
}

#[test]
fn a_handle_from_another_graph_is_rejected() {
    let mut other = GraphBuilder::new();
    other.create_texture("a", tex(Rgba8Unorm));
    let foreign = other.create_texture("b", tex(Rgba8Unorm));

    let mut g = GraphBuilder::new();
    let mut p = g.add_compute_pass("cs");
    p.sampled(foreign);
    p.side_effect();

    let error = only_error(&g.build());
    assert_eq!(
        error,
        GraphError::ForeignHandle {
            pass: "cs".into(),
            resource: "Texture#1@v0".into(),
        }
    );
    assert_eq!(
        error.to_string(),
        r#"pass "cs" uses "Texture#1@v0", which belongs to another graph"#
    );
}

/// A foreign handle whose index happens to exist here is caught by its version, when this
/// graph never handed that version out.
#[test]
fn a_foreign_handle_to_a_version_this_graph_never_made_is_rejected() {
    let mut other = GraphBuilder::new();
    let t = other.create_texture("t", tex(Rgba8Unorm));
    let newer = clear_pass(&mut other, "fill", t);

    let mut g = GraphBuilder::new();
    g.create_texture("mine", tex(Rgba8Unorm));
    let mut copy = g.add_transfer_pass("copy");
    copy.copy_dst(newer);
    copy.side_effect();

    assert_eq!(
        only_error(&g.build()).to_string(),
        r#"pass "copy" uses "Texture#0@v1", which belongs to another graph"#
    );
}
