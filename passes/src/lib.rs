//! rgraph's pass plugins: deferred shading with MSAA (G-buffer, tiled and volume lighting,
//! resolve), the visibility buffer rasterised in compute, forward MSAA, seed 001's
//! off-screen particles, and the post passes (tone mapping, auto exposure, FXAA, SSAO, the
//! light pre-pass, debug views). They draw a [`rgraph_scene::Scene`].
//!
//! - [`register`]: adds the pass plugins graph files name (`gbuffer`, `edge_stencil`,
//!   `light_edge`, `light_nonedge`, `light_tiled`, `visibility`, `visibility_compute`,
//!   `resolve`, `tonemap`, `debug_view`, ...) to a [`Registry`]. Graph files are their only
//!   interface: each plugin's slots and parameters are in the pass catalogue,
//!   `docs/reference/passes.md`.
//! - [`variant`]: which shader variants a plan builds for a scene's features.
//! - [`layers`]: the material layers a G-buffer stores, and which a plan's G-buffer
//!   lighting leaves out.
//! - [`host`]: what the host application hands the plugins (the scene, overrides, frame
//!   inputs).
//! - [`gpu_scene`] (feature `gpu`): the scene on the device, shared by the plugins and
//!   reusable by other passes that draw it.
//!
//! Scene textures are uploaded with a full mip chain made on the CPU (sRGB-correct box
//! filter), and sampled as their glTF sampler says.
//!
//! # A frame of the plugins, validated without a GPU
//!
//! A registry with a [`Host`] draws its scene; declaring, loading and compiling need no
//! device (the plugins parse and reflect their WGSL with naga while loading), so an engine's
//! build script or CI checks its graph files this way. Executing the loaded graph is
//! rgraph-core's [`Executor`](rgraph_core::gpu::Executor), as for any graph.
//!
//! ```
//! use std::sync::Arc;
//!
//! use rgraph_core::file::{load_str_with, GraphParams, Registry};
//! use rgraph_core::CompileOptions;
//! use rgraph_passes::{Host, Overrides};
//! use rgraph_scene::analysis::Features;
//! use rgraph_scene::Scene;
//!
//! // A visibility buffer rasterised in compute at 4x MSAA, lit and resolved in one tiled
//! // compute pass, tone mapped into the engine's target.
//! const GRAPH: &str = r#"Graph(
//!     resources: {
//!         "samples": Buffer(per_sample: 8, samples: 4),
//!         "resolved": Texture(format: "rgba16float"),
//!         "target": ImportedTexture(format: "rgba8unorm-srgb"),
//!     },
//!     passes: [
//!         (name: "visibility", plugin: "visibility_compute",
//!          outputs: { "samples": "samples" }),
//!         (name: "light tiled", plugin: "light_tiled",
//!          inputs: { "samples": "samples" }, outputs: { "resolved": "resolved" }),
//!         (name: "tonemap", plugin: "tonemap", params: (operator: aces),
//!          inputs: { "hdr": "resolved" }, outputs: { "color": "target" }),
//!     ],
//!     outputs: ["target"],
//! )"#;
//!
//! let scene = Arc::new(Scene::load("builtin:spheres")?);
//! let host = Arc::new(Host::new(scene.clone(), Overrides::default()));
//! let mut registry = Registry::with_builtins();
//! rgraph_passes::register(&mut registry, Some(host));
//! let graph = load_str_with("frame.ron", GRAPH, &registry, &GraphParams::new())?;
//!
//! // Compiled for the scene's features, against what every WebGPU device guarantees.
//! let plan = graph.compile_for(&CompileOptions::default(), &Features::of(&scene).names())?;
//! let passes: Vec<&str> = plan.passes.iter().map(|p| p.name.as_str()).collect();
//! assert_eq!(passes, ["visibility", "light tiled", "tonemap"]);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

#![deny(missing_docs)]

mod common;
#[cfg(feature = "gpu")]
pub mod gpu_scene;
pub mod host;
#[cfg(feature = "gpu")]
mod kept;
pub mod layers;
mod passes;
mod plugins;
pub mod pose;
mod shaders;
pub mod shadows;
pub mod variant;

use std::sync::Arc;

use rgraph_core::file::Registry;

pub use host::{Background, Exposure, FrameInputs, FrameInputsError, Host, LightPose, Overrides};
pub use shadows::{ShadowFilter, Shadows};

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
