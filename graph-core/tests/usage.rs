//! Usage derivation: each resource gets exactly the usages its live accesses need.

use crate::common;

use common::{plan, tex, CLEAR};
use rgraph_core::types::TextureFormat::{Depth24PlusStencil8, Rgba16Float, Rgba8Unorm};
use rgraph_core::types::{BufferUsages, TextureUsages};
use rgraph_core::{
    AspectAccess, BufferDesc, BufferRole, ColorLoad, CompileOptions, DeviceProfile, Graph,
    GraphBuilder, Plan,
};

fn texture_usage(plan: &Plan, name: &str) -> TextureUsages {
    plan.find(name).unwrap().texture_usage
}

#[test]
fn a_gbuffer_target_is_attached_then_sampled() {
    let mut g = GraphBuilder::new();
    let [albedo, hdr] = ["albedo", "hdr"].map(|n| g.create_texture(n, tex(Rgba16Float)));
    let albedo = g.add_render_pass("gbuffer").color_output(albedo, CLEAR);
    let mut p = g.add_render_pass("light");
    p.sampled(albedo);
    let hdr = p.color_output(hdr, CLEAR);
    g.export(hdr);
    let plan = plan(&g.build());

    assert_eq!(
        texture_usage(&plan, "albedo"),
        TextureUsages::RENDER_ATTACHMENT | TextureUsages::TEXTURE_BINDING
    );
    assert_eq!(
        texture_usage(&plan, "hdr"),
        TextureUsages::RENDER_ATTACHMENT | TextureUsages::COPY_SRC
    );
}

#[test]
fn storage_and_copies_have_their_usages() {
    let mut g = GraphBuilder::new();
    let [a, b] = ["a", "b"].map(|n| g.create_texture(n, tex(Rgba8Unorm)));
    let a = g.add_compute_pass("fill").storage_write(a);
    let mut copy = g.add_transfer_pass("copy");
    copy.copy_src(a);
    let b = copy.copy_dst(b);
    let mut p = g.add_compute_pass("use");
    p.storage_read(b);
    p.side_effect();
    let plan = plan(&g.build());

    assert_eq!(
        texture_usage(&plan, "a"),
        TextureUsages::STORAGE_BINDING | TextureUsages::COPY_SRC
    );
    assert_eq!(
        texture_usage(&plan, "b"),
        TextureUsages::COPY_DST | TextureUsages::STORAGE_BINDING
    );
}

#[test]
fn buffers_get_their_roles_declared_extras_and_export_copies() {
    let mut g = GraphBuilder::new();
    let lights = g.create_buffer("lights", BufferDesc::new(1024));
    let mut readback = BufferDesc::new(256);
    readback.extra_usage = BufferUsages::MAP_READ;
    let stats = g.create_buffer("stats", readback);
    let mut cull = g.add_compute_pass("cull");
    let lights = cull.buffer(
        lights,
        BufferRole::Storage {
            read: false,
            write: true,
        },
    );
    let stats = cull.buffer(
        stats,
        BufferRole::Storage {
            read: false,
            write: true,
        },
    );
    let mut p = g.add_compute_pass("shade");
    p.buffer(lights, BufferRole::Uniform);
    p.side_effect();
    g.export(stats);
    let plan = plan(&g.build());

    let usage = |name| plan.find(name).unwrap().buffer_usage;
    assert_eq!(
        usage("lights"),
        BufferUsages::STORAGE | BufferUsages::UNIFORM
    );
    assert_eq!(
        usage("stats"),
        BufferUsages::STORAGE | BufferUsages::MAP_READ | BufferUsages::COPY_SRC
    );
}

/// A 4x color target and a 4x depth target cleared and resolved (or dropped) in one pass,
/// plus "debug", a culled pass that would have read the color: nothing that runs reads
/// them after their pass.
fn msaa_pass() -> Graph {
    let mut g = GraphBuilder::new();
    let msaa = g.create_texture("msaa", tex(Rgba8Unorm).samples(4));
    let depth = g.create_texture("depth", tex(Depth24PlusStencil8).samples(4));
    let [out, debug] = ["out", "debug"].map(|n| g.create_texture(n, tex(Rgba8Unorm)));
    let mut p = g.add_render_pass("draw");
    let msaa = p.color_output(msaa, CLEAR);
    p.depth_stencil(depth, AspectAccess::Clear(1.0), AspectAccess::Clear(0));
    let out = p.resolve_output(msaa, out);
    g.export(out);
    let mut p = g.add_render_pass("debug");
    p.sampled(msaa);
    p.color_output(debug, CLEAR);
    g.build()
}

#[test]
fn targets_that_never_leave_their_pass_are_transient() {
    let plan = plan(&msaa_pass());
    let transient = TextureUsages::RENDER_ATTACHMENT | TextureUsages::TRANSIENT_ATTACHMENT;
    assert_eq!(texture_usage(&plan, "msaa"), transient);
    assert_eq!(texture_usage(&plan, "depth"), transient);
    assert_eq!(
        texture_usage(&plan, "out"),
        TextureUsages::RENDER_ATTACHMENT | TextureUsages::COPY_SRC
    );
}

#[test]
fn a_profile_without_transient_attachments_gets_none() {
    let mut profile = DeviceProfile::webgpu();
    profile.transient_attachments = false;
    let options = CompileOptions {
        profile,
        ..CompileOptions::default()
    };
    let plan = msaa_pass().compile(&options).unwrap();
    assert_eq!(
        texture_usage(&plan, "msaa"),
        TextureUsages::RENDER_ATTACHMENT
    );
}

#[test]
fn a_resource_only_culled_passes_use_has_no_usage() {
    let plan = plan(&msaa_pass());
    assert_eq!(texture_usage(&plan, "debug"), TextureUsages::empty());
}

/// Loading it in a second pass keeps the samples in memory between passes.
#[test]
fn a_target_read_after_its_pass_is_not_transient() {
    let mut g = GraphBuilder::new();
    let msaa = g.create_texture("msaa", tex(Rgba8Unorm).samples(4));
    let out = g.create_texture("out", tex(Rgba8Unorm));
    let msaa = g.add_render_pass("opaque").color_output(msaa, CLEAR);
    let mut p = g.add_render_pass("transparent");
    let msaa = p.color_output(msaa, ColorLoad::Load);
    let out = p.resolve_output(msaa, out);
    g.export(out);
    let plan = plan(&g.build());

    assert_eq!(
        texture_usage(&plan, "msaa"),
        TextureUsages::RENDER_ATTACHMENT
    );
}
