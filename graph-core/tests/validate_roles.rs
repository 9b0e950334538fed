//! Role errors: a pass kind that cannot use a role, one texture in two incompatible roles,
//! and formats that cannot serve the role they were given.

use crate::common;

use common::{clear_pass, only_error, plan, tex, CLEAR};
use rgraph_core::types::TextureFormat::{
    Depth24PlusStencil8, Depth32Float, R32Float, Rgba16Float, Rgba8Unorm, Rgba8UnormSrgb, Stencil8,
};
use rgraph_core::{
    Aspect, AspectAccess, BufferDesc, BufferRole, GraphBuilder, GraphError, Role, TextureRole,
};

#[test]
fn a_render_pass_cannot_copy() {
    let mut g = GraphBuilder::new();
    let src = g.create_texture("src", tex(Rgba8Unorm));
    let src = clear_pass(&mut g, "fill", src);
    let out = g.create_texture("out", tex(Rgba8Unorm));
    let mut blit = g.add_render_pass("blit");
    blit.copy_src(src);
    let out = blit.color_output(out, CLEAR);
    g.export(out);

    let error = only_error(&g.build());
    assert_eq!(
        error,
        GraphError::RoleNotAllowed {
            pass: "blit".into(),
            kind: "render".into(),
            role: "copy source",
            resource: "src".into(),
        }
    );
    assert_eq!(
        error.to_string(),
        r#"render pass "blit" cannot use "src" as a copy source"#
    );
}

#[test]
fn a_compute_pass_cannot_have_a_color_attachment() {
    let mut g = GraphBuilder::new();
    let t = g.create_texture("t", tex(Rgba8Unorm));
    let mut cs = g.add_compute_pass("cs");
    let t = cs.color_output(t, CLEAR);
    g.export(t);

    assert_eq!(
        only_error(&g.build()).to_string(),
        r#"compute pass "cs" cannot use "t" as a color attachment"#
    );
}

#[test]
fn a_compute_pass_cannot_bind_a_vertex_buffer() {
    let mut g = GraphBuilder::new();
    let b = g.import_buffer("vertices", BufferDesc::new(256));
    let mut cs = g.add_compute_pass("cs");
    cs.buffer(b, BufferRole::Vertex);
    cs.side_effect();

    assert_eq!(
        only_error(&g.build()).to_string(),
        r#"compute pass "cs" cannot use "vertices" as a vertex buffer"#
    );
}

#[test]
fn a_transfer_pass_can_only_copy() {
    let mut g = GraphBuilder::new();
    let t = g.create_texture("t", tex(Rgba8Unorm));
    let mut copy = g.add_transfer_pass("copy");
    let t = copy.storage_write(t);
    g.export(t);

    assert_eq!(
        only_error(&g.build()).to_string(),
        r#"transfer pass "copy" cannot use "t" as a storage texture"#
    );
}

#[test]
fn sampling_the_color_target_of_the_same_pass_is_a_usage_conflict() {
    let mut g = GraphBuilder::new();
    let t = g.create_texture("t", tex(Rgba8Unorm));
    let t = clear_pass(&mut g, "fill", t);
    let mut p = g.add_render_pass("feedback");
    p.sampled(t);
    let t = p.color_output(t, CLEAR);
    g.export(t);

    let error = only_error(&g.build());
    assert_eq!(
        error,
        GraphError::UsageConflict {
            pass: "feedback".into(),
            resource: "t".into(),
            first: "sampled texture",
            second: "color attachment",
        }
    );
    assert_eq!(
        error.to_string(),
        r#"pass "feedback" uses "t" both as a sampled texture and as a color attachment"#
    );
}

#[test]
fn writing_one_texture_twice_in_a_pass_is_a_usage_conflict() {
    let mut g = GraphBuilder::new();
    let t = g.create_texture("t", tex(Rgba8Unorm));
    let mut p = g.add_render_pass("p");
    p.color_output(t, CLEAR);
    let t = p.storage_write(t);
    g.export(t);

    assert_eq!(
        only_error(&g.build()).to_string(),
        r#"pass "p" uses "t" both as a color attachment and as a storage texture"#
    );
}

/// A prepass clears "depth"; then pass `name` draws into the exported "out" while it
/// samples the depth aspect of "depth" and attaches it, depth read-only and stencil
/// with `stencil`.
fn sample_attached_depth(name: &str, stencil: AspectAccess<u32>) -> rgraph_core::Graph {
    let mut g = GraphBuilder::new();
    let depth = g.create_texture("depth", tex(Depth24PlusStencil8));
    let out = g.create_texture("out", tex(Rgba8Unorm));
    let depth = g.add_render_pass("prepass").depth_stencil(
        depth,
        AspectAccess::Clear(1.0),
        AspectAccess::Clear(0),
    );
    let mut p = g.add_render_pass(name);
    let out = p.color_output(out, CLEAR);
    p.depth_stencil(depth, AspectAccess::ReadOnly, stencil);
    p.sampled_aspect(depth, Aspect::DepthOnly);
    g.export(out);
    g.build()
}

#[test]
fn sampling_a_writable_depth_stencil_attachment_is_rejected() {
    let error = only_error(&sample_attached_depth("decals", AspectAccess::Load));
    assert_eq!(
        error,
        GraphError::SampledWhileWritable {
            pass: "decals".into(),
            resource: "depth".into(),
        }
    );
    assert_eq!(
        error.to_string(),
        r#"pass "decals" samples depth-stencil texture "depth" while writing it; attach it read-only in both aspects to sample it in the same pass"#
    );
}

#[test]
fn sampling_a_depth_stencil_attachment_read_only_in_both_aspects_is_allowed() {
    let graph = sample_attached_depth("fog", AspectAccess::ReadOnly);
    assert_eq!(plan(&graph).passes.len(), 2);
}

/// Imports a 64x64 texture "t" of `format`, lets `bind` declare a pass "p" that uses it,
/// and returns the single error the graph reports. Validation does not depend on culling,
/// so "p" need not be live.
fn format_role_error(
    format: rgraph_core::types::TextureFormat,
    bind: impl FnOnce(&mut GraphBuilder, rgraph_core::TextureHandle),
) -> GraphError {
    let mut g = GraphBuilder::new();
    let t = g.import_texture("t", tex(format));
    bind(&mut g, t);
    only_error(&g.build())
}

#[test]
fn a_depth_format_cannot_be_a_color_attachment() {
    let error = format_role_error(Depth32Float, |g, t| {
        g.add_render_pass("p").color_output(t, CLEAR);
    });
    assert_eq!(
        error,
        GraphError::FormatRole {
            pass: "p".into(),
            resource: "t".into(),
            format: "depth32float".into(),
            role: "color attachment",
            why: "it is a depth-stencil format".into(),
        }
    );
    assert_eq!(
        error.to_string(),
        r#"pass "p": "t" (depth32float) cannot be a color attachment: it is a depth-stencil format"#
    );
}

#[test]
fn a_color_format_cannot_be_a_depth_stencil_attachment() {
    let error = format_role_error(Rgba8Unorm, |g, t| {
        g.add_render_pass("p")
            .depth_stencil(t, AspectAccess::Clear(1.0), AspectAccess::ReadOnly);
    });
    assert_eq!(
        error.to_string(),
        r#"pass "p": "t" (rgba8unorm) cannot be a depth-stencil attachment: it is not a depth-stencil format"#
    );
}

#[test]
fn depth32float_has_no_stencil_to_write() {
    let error = format_role_error(Depth32Float, |g, t| {
        g.add_render_pass("p")
            .depth_stencil(t, AspectAccess::Load, AspectAccess::Clear(0));
    });
    assert_eq!(
        error.to_string(),
        r#"pass "p": "t" (depth32float) cannot be a depth-stencil attachment: the format has no stencil aspect to write"#
    );
}

#[test]
fn a_non_storage_format_cannot_be_a_storage_texture() {
    let mut g = GraphBuilder::new();
    let t = g.create_texture("t", tex(Rgba8UnormSrgb));
    let t = g.add_compute_pass("cs").storage_write(t);
    g.export(t);

    assert_eq!(
        only_error(&g.build()).to_string(),
        r#"pass "cs": "t" (rgba8unorm-srgb) cannot be a storage texture: it is not a storage format on webgpu defaults"#
    );
}

#[test]
fn a_render_pass_may_also_write_storage() {
    let mut g = GraphBuilder::new();
    let t = g.create_texture("t", tex(Rgba16Float));
    let counts = g.create_texture("counts", tex(Rgba8Unorm));
    let mut p = g.add_render_pass("p");
    let t = p.color_output(t, CLEAR);
    let counts = p.storage_write(counts);
    g.export(t);
    g.export(counts);

    assert_eq!(plan(&g.build()).passes.len(), 1);
}

/// A depth prepass on a depth-only format attaches the stencil it does not have as
/// read-only; that must neither read the fresh texture nor order anything.
#[test]
fn a_missing_aspect_attached_read_only_reads_nothing() {
    let mut g = GraphBuilder::new();
    let depth = g.create_texture("depth", tex(Depth32Float));
    let mut p = g.add_render_pass("prepass");
    let depth = p.depth_stencil(depth, AspectAccess::Clear(1.0), AspectAccess::ReadOnly);
    g.export(depth);
    let mask = g.create_texture("mask", tex(Stencil8));
    let mut p = g.add_render_pass("mask");
    let mask = p.depth_stencil(mask, AspectAccess::ReadOnly, AspectAccess::Clear(0));
    g.export(mask);
    let graph = g.build();

    let plan = plan(&graph);
    let roles: Vec<Role> = graph.passes().iter().map(|p| p.accesses[0].role).collect();
    assert_eq!(
        roles,
        [
            Role::Texture(TextureRole::DepthStencil {
                depth: AspectAccess::Clear(1.0),
                stencil: AspectAccess::Absent,
            }),
            Role::Texture(TextureRole::DepthStencil {
                depth: AspectAccess::Absent,
                stencil: AspectAccess::Clear(0),
            }),
        ]
    );
    assert!(plan.passes.iter().all(|p| p.reads.is_empty()));
}

#[test]
fn an_aspect_the_format_has_cannot_be_declared_absent() {
    let error = format_role_error(Depth24PlusStencil8, |g, t| {
        g.add_render_pass("p")
            .depth_stencil(t, AspectAccess::Load, AspectAccess::Absent);
    });
    assert_eq!(
        error.to_string(),
        r#"pass "p": "t" (depth24plus-stencil8) cannot be a depth-stencil attachment: the format has a stencil aspect; attach it read-only instead"#
    );
}

#[test]
fn a_depth_only_format_has_no_stencil_view_to_sample() {
    let error = format_role_error(Depth32Float, |g, t| {
        g.add_compute_pass("p")
            .sampled_aspect(t, Aspect::StencilOnly);
    });
    assert_eq!(
        error.to_string(),
        r#"pass "p": "t" (depth32float) cannot be a sampled texture: the format has no stencil aspect"#
    );
}

/// wgpu has no sample type for both aspects of a combined format at once.
#[test]
fn a_combined_depth_stencil_format_is_sampled_one_aspect_at_a_time() {
    let error = format_role_error(Depth24PlusStencil8, |g, t| {
        g.add_compute_pass("p").sampled(t);
    });
    assert_eq!(
        error.to_string(),
        r#"pass "p": "t" (depth24plus-stencil8) cannot be a sampled texture: sample one aspect of a combined depth-stencil format (Aspect::DepthOnly or Aspect::StencilOnly)"#
    );
}

/// WebGPU guarantees read-write storage access only for the 32-bit single-channel formats.
#[test]
fn read_write_storage_needs_a_format_that_supports_it() {
    let mut g = GraphBuilder::new();
    let ok = g.import_texture("ok", tex(R32Float));
    let bad = g.import_texture("bad", tex(Rgba8Unorm));
    let mut cs = g.add_compute_pass("cs");
    cs.storage_read_write(ok);
    cs.storage_read_write(bad);
    cs.side_effect();

    assert_eq!(
        only_error(&g.build()).to_string(),
        r#"pass "cs": "bad" (rgba8unorm) cannot be a storage texture: it does not support read-write storage access on webgpu defaults"#
    );
}

#[test]
fn a_multisampled_texture_cannot_be_a_storage_texture() {
    let mut g = GraphBuilder::new();
    let t = g.import_texture("t", tex(R32Float).samples(4));
    let mut cs = g.add_compute_pass("cs");
    cs.storage_write(t);
    cs.side_effect();

    assert_eq!(
        only_error(&g.build()).to_string(),
        r#"pass "cs": "t" (r32float) cannot be a storage texture: it is multisampled"#
    );
}
