//! The deferred passes, one module each: a pass's parameters, slots and `Plugin::setup`,
//! and (feature `gpu`) its recording, as rgraph-core's plugins keep theirs. They import
//! what they share from [`crate::common`], and from each other only one way (the
//! transparent pass draws as the forward pass does, the tiled light pass resolves as the
//! resolve pass does); [`crate::plugins`] registers them by name.

pub(crate) mod auto_exposure;
pub(crate) mod background;
pub(crate) mod debug_view;
pub(crate) mod depth_downsample;
pub(crate) mod depth_pyramid;
pub(crate) mod edge_stencil;
pub(crate) mod forward;
pub(crate) mod fxaa;
pub(crate) mod gbuffer;
pub(crate) mod gbuffer_resolve;
pub(crate) mod keys_depth;
pub(crate) mod light;
pub(crate) mod light_prepass;
pub(crate) mod light_tiled;
pub(crate) mod motion_vectors;
pub(crate) mod particle_edges;
pub(crate) mod particles;
pub(crate) mod points_lines;
pub(crate) mod resolve;
pub(crate) mod shadow_maps;
pub(crate) mod shadow_raster;
pub(crate) mod shadow_resolve;
pub(crate) mod ssao;
pub(crate) mod taa;
pub(crate) mod tonemap;
pub(crate) mod transparent;
pub(crate) mod visibility;
pub(crate) mod visibility_compute;
