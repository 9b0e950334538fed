//! Deferred shading with MSAA as rgraph pass plugins, and the scenes they render.
//!
//! - [`scene`]: the CPU scene model and its loaders.
//! - [`analysis`]: what a scene needs, as the feature names pipeline conditions test.
//! - [`plugins`]: the pass plugins graph files name (`gbuffer`, `edge_stencil`,
//!   `light_edge`, `light_nonedge`, `light_tiled`, `resolve`, `tonemap`, `debug_view`),
//!   the baselines' `forward` and `gbuffer_resolve`, `transparent` and
//!   `composite_transparent` for alpha BLEND meshes, and seed 001's off-screen particles:
//!   `particles`, `composite_particles`, `depth_downsample` and `particle_edges`.
//! - [`gpu_scene`] (feature `gpu`): the scene on the device, shared by the plugins and
//!   reusable by other passes that draw it.
//!
//! Scene textures are uploaded with a full mip chain made on the CPU (sRGB-correct box
//! filter), and sampled as their glTF sampler says.

pub mod analysis;
mod common;
#[cfg(feature = "gpu")]
pub mod gpu_scene;
pub mod host;
mod passes;
pub mod plugins;
pub mod scene;
mod shaders;

use std::sync::Arc;

use graph_core::file::Registry;

/// The math crate of the scene API (`DVec3` positions, `DMat4` transforms), so callers
/// building a [`scene::Scene`] in code use the same version.
pub use glam;
pub use host::{Background, Exposure, FrameInputs, FrameInputsError, Host, LightPose, Overrides};

/// Adds this crate's pass plugins to `registry`, so graph files can name them. With
/// `host: None` the plugins declare and validate passes but draw nothing (see [`host`]).
/// Shaders are compiled for the scene's features ([`analysis::Variant`]).
pub fn register(registry: &mut Registry, host: Option<Arc<Host>>) {
    register_with(registry, host, analysis::Variants::Scene);
}

/// [`register`], choosing which shader variants the plugins compile:
/// [`Variants::General`](analysis::Variants::General) renders the same images with the
/// general shaders, to check or compare specialisation against.
pub fn register_with(
    registry: &mut Registry,
    host: Option<Arc<Host>>,
    variants: analysis::Variants,
) {
    plugins::register(registry, host, variants);
}
