//! Device-side helpers the deferred passes' recordings share (feature `gpu`): one way to
//! build a render pipeline and a cache of pipelines keyed by what the plan decides at
//! execution (formats, sample counts) ([`pipeline`]), the bind group of a pass's input
//! textures ([`bindings`]), the device objects of a pass that reads them
//! ([`input_pass`]), the recording of passes that draw the scene's meshes
//! ([`scene_draw`]), the opaque draws as compute rasterisers see them
//! ([`raster_draws`]), their triangles binned to tiles ([`tile_bins`]), and groups of
//! storage buffers ([`storage`]).

pub(crate) mod bindings;
pub(crate) mod input_pass;
pub(crate) mod pipeline;
pub(crate) mod raster_draws;
pub(crate) mod scene_draw;
pub(crate) mod storage;
pub(crate) mod tile_bins;

use std::sync::Arc;

use crate::gpu_scene::GpuScene;
pub(crate) use input_pass::{GroupBuffers, InputPass};
pub(crate) use pipeline::{additive, compute_pipeline, PipelineDesc};

/// geometry.wgsl's `SPLIT_IDS` for a visibility buffer of `format`: rg16uint holds an ID
/// in two halves, r32uint whole.
pub(crate) fn split_ids(format: wgpu::TextureFormat) -> f64 {
    f64::from(u8::from(format == wgpu::TextureFormat::Rg16Uint))
}

/// The stencil bit edge pixels carry (seed 000's 0x80): the edge pass marks it, the light
/// passes test it.
pub(crate) const EDGE_STENCIL: u32 = 0x80;

/// What a recorder built for one scene upload, rebuilt by `build` when the frame's scene
/// is another upload (another device, or a new host): its module and layouts are made
/// on the scene's device against the scene's bind group layouts.
pub(crate) fn per_scene<'s, S>(
    slot: &'s mut Option<(Arc<GpuScene>, S)>,
    scene: &Arc<GpuScene>,
    build: impl FnOnce() -> S,
) -> &'s mut S {
    if slot
        .as_ref()
        .is_some_and(|(built, _)| !built.same_upload(scene))
    {
        *slot = None;
    }
    &mut slot.get_or_insert_with(|| (scene.clone(), build())).1
}

/// What a recorder built for one device, rebuilt by `build` on another: for passes whose
/// objects do not depend on the scene's upload (the scene's group 0 layout is the same for
/// every upload).
pub(crate) fn per_device<'s, S>(
    slot: &'s mut Option<(wgpu::Device, S)>,
    device: &wgpu::Device,
    build: impl FnOnce() -> S,
) -> &'s mut S {
    if slot.as_ref().is_some_and(|(built, _)| built != device) {
        *slot = None;
    }
    &mut slot.get_or_insert_with(|| (device.clone(), build())).1
}
