//! rgraph's pass plugins: deferred shading with MSAA (G-buffer, tiled and volume lighting,
//! resolve), the visibility buffer rasterised in compute, forward MSAA, seed 001's
//! off-screen particles, and the post passes (tone mapping, auto exposure, FXAA, SSAO, the
//! light pre-pass, debug views). They draw a [`rgraph_scene::Scene`].
//!
//! - [`plugins`]: the pass plugins graph files name (`gbuffer`, `edge_stencil`,
//!   `light_edge`, `light_nonedge`, `light_tiled`, `resolve`, `tonemap`, `debug_view`),
//!   the baselines' `forward` and `gbuffer_resolve`, `transparent` and
//!   `composite_transparent` for alpha BLEND meshes, and seed 001's off-screen particles:
//!   `particles`, `composite_particles`, `depth_downsample` and `particle_edges`.
//! - [`variant`]: which shader variants a plan builds for a scene's features.
//! - [`host`]: what the host application hands the plugins (the scene, overrides, frame
//!   inputs).
//! - [`gpu_scene`] (feature `gpu`): the scene on the device, shared by the plugins and
//!   reusable by other passes that draw it.
//!
//! Scene textures are uploaded with a full mip chain made on the CPU (sRGB-correct box
//! filter), and sampled as their glTF sampler says.

mod common;
#[cfg(feature = "gpu")]
pub mod gpu_scene;
pub mod host;
mod passes;
pub mod plugins;
mod shaders;
pub mod variant;

use std::sync::Arc;

use graph_core::file::Registry;

pub use host::{Background, Exposure, FrameInputs, FrameInputsError, Host, LightPose, Overrides};

/// Adds this crate's pass plugins to `registry`, so graph files can name them. With
/// `host: None` the plugins declare and validate passes but draw nothing (see [`host`]).
/// Shaders are compiled for the scene's features ([`variant::Variant`]).
pub fn register(registry: &mut Registry, host: Option<Arc<Host>>) {
    register_with(registry, host, variant::Variants::Scene);
}

/// [`register`], choosing which shader variants the plugins compile:
/// [`Variants::General`](variant::Variants::General) renders the same images with the
/// general shaders, to check or compare specialisation against.
pub fn register_with(
    registry: &mut Registry,
    host: Option<Arc<Host>>,
    variants: variant::Variants,
) {
    plugins::register(registry, host, variants);
}
