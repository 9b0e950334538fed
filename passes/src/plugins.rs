//! The deferred-shading pass plugins. A graph file chains them as
//! `gbuffer` → `edge_stencil` → `light_edge` + `light_nonedge` → `resolve` → `tonemap`
//! (the seeds' fragment path), or `gbuffer` → `light_tiled` → `tonemap` (lighting and
//! resolve in one compute pass), or `visibility` (or `visibility_compute`, rasterising in
//! compute, with `keys_depth` for the transparent pass and `depth_pyramid` for culling
//! its clusters by occlusion) → `light_tiled` → `tonemap` (a
//! visibility buffer, whose triangles the compute pass rebuilds and shades),
//! with `debug_view` passes reading the G-buffer beside them; `pipelines/deferred_*.ron`
//! are complete examples. Each plugin's module documents its parameters and slots.
//! The baselines add `forward` (the scene lit per fragment, pipelines/forward_msaa_4x.ron
//! and reference_ssaa16.ron) and `gbuffer_resolve` (the G-buffer averaged before
//! lighting, pipelines/deferred_gbuffer_resolve_4x.ron). Every pipeline that renders the
//! lit scene adds `transparent` and `composite_transparent` under `when: "blend"`: alpha
//! BLEND meshes, which the opaque passes skip, drawn after lighting and composited onto
//! the resolved image; and `points_lines` under `when: "points_lines"`, glTF points
//! and lines, unlit, composited after them by `composite_transparent`. `fxaa` is a post
//! filter on the tone-mapped image
//! (pipelines/deferred_noaa_fxaa.ron, deferred_msaa_4x_fxaa.ron). `ssao` and `ssao_blur`
//! compute screen-space ambient occlusion from the G-buffer, which the light passes take
//! as their optional `ao` input (pipelines/deferred_msaa_4x_ssao.ron).
//! `shadow_maps` draws the shadowed lights' depth into a shadow atlas, which the light
//! passes (`light_tiled`, `light_edge`, `light_nonedge`) read as their optional `shadows`
//! input, under `when: "shadows"`.
//! `background` draws what shows where nothing is (the host's `Background`: the
//! environment, or coverage for a colour or transparent output) under `when:
//! "background"`, before the transparent composite.
//! `light_prepass_gbuffer` and `light_prepass_material` are a light pre-pass renderer's
//! geometry passes around the light passes' `accumulate: light`
//! (pipelines/light_prepass_msaa_4x.ron). The `particles_*` pipelines draw the scene's
//! particle emitters after the transparent composite, at full resolution or off screen (`depth_downsample`, `particles`,
//! `particle_edges`, `composite_particles`: seed 001).
//!
//! The G-buffer slots every pass uses the same names for: `albedo`, `normal`,
//! `material`, `view_depth`, `hdr` and `depth` (the multisampled depth-stencil).
//!
//! The passes that test or write depth (`gbuffer`, `forward`, `gbuffer_resolve`, `transparent`,
//! `light_edge`, `light_nonedge`) take an optional `reversed_z`. Left out, the depth
//! convention follows the depth format the compile picks: reversed-Z for float depth,
//! standard Z for unorm depth (see `common/depth.rs`), so the passes agree whichever format a
//! device or a scene gets. Given, it holds for any format, and passes sharing a depth
//! buffer must give the same.

use std::sync::Arc;

use rgraph_core::file::Registry;

use crate::common::plugin::Shared;
use crate::host::Host;
use crate::passes::auto_exposure::AutoExposure;
use crate::passes::background::Background;
use crate::passes::debug_view::DebugView;
use crate::passes::depth_downsample::DepthDownsample;
use crate::passes::depth_pyramid::DepthPyramid;
use crate::passes::edge_stencil::EdgeStencil;
use crate::passes::forward::Forward;
use crate::passes::fxaa::Fxaa;
use crate::passes::gbuffer::GBuffer;
use crate::passes::gbuffer_resolve::GBufferResolve;
use crate::passes::keys_depth::KeysDepth;
use crate::passes::light::{LightEdge, LightNonEdge};
use crate::passes::light_prepass::{LightPrepassGBuffer, LightPrepassMaterial};
use crate::passes::light_tiled::LightTiled;
use crate::passes::motion_vectors::MotionVectors;
use crate::passes::particle_edges::ParticleEdges;
use crate::passes::particles::{CompositeParticles, Particles};
use crate::passes::points_lines::PointsLinesPass;
use crate::passes::resolve::Resolve;
use crate::passes::shadow_maps::ShadowMaps;
use crate::passes::shadow_raster::ShadowRaster;
use crate::passes::shadow_resolve::ShadowResolve;
use crate::passes::ssao::{Ssao, SsaoBlur};
use crate::passes::taa::Taa;
use crate::passes::tonemap::Tonemap;
use crate::passes::transparent::{CompositeTransparent, Transparent};
use crate::passes::visibility::Visibility;
use crate::passes::visibility_compute::VisibilityCompute;
use crate::variant::Variants;

/// Adds every deferred plugin, sharing `host`, compiling shaders as `variants` says.
pub(crate) fn register(registry: &mut Registry, host: Option<Arc<Host>>, variants: Variants) {
    let shared = Shared::new(host, variants);
    registry
        .register(GBuffer(shared.clone()))
        .register(EdgeStencil(shared.clone()))
        .register(LightNonEdge(shared.clone()))
        .register(LightEdge(shared.clone()))
        .register(LightTiled(shared.clone()))
        .register(MotionVectors(shared.clone()))
        .register(Visibility(shared.clone()))
        .register(VisibilityCompute(shared.clone()))
        .register(KeysDepth(shared.clone()))
        .register(DepthPyramid(shared.clone()))
        .register(Resolve(shared.clone()))
        .register(ShadowMaps(shared.clone()))
        .register(ShadowRaster(shared.clone()))
        .register(ShadowResolve(shared.clone()))
        .register(Tonemap(shared.clone()))
        .register(AutoExposure(shared.clone()))
        .register(DebugView(shared.clone()))
        .register(Forward(shared.clone()))
        .register(GBufferResolve(shared.clone()))
        .register(Fxaa(shared.clone()))
        .register(Taa(shared.clone()))
        .register(Ssao(shared.clone()))
        .register(LightPrepassGBuffer(shared.clone()))
        .register(LightPrepassMaterial(shared.clone()))
        .register(SsaoBlur(shared.clone()))
        .register(Transparent(shared.clone()))
        .register(CompositeTransparent(shared.clone()))
        .register(PointsLinesPass(shared.clone()))
        .register(Background(shared.clone()))
        .register(Particles(shared.clone()))
        .register(CompositeParticles(shared.clone()))
        .register(DepthDownsample(shared.clone()))
        .register(ParticleEdges(shared));
}
