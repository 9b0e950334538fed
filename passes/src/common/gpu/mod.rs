//! Device-side helpers the deferred passes' recordings share (feature `gpu`): the one
//! shape of a pass's recording ([`recorder`]), one way to build a render pipeline and a
//! cache of pipelines keyed by what the plan decides at execution (formats, sample
//! counts) ([`pipeline`]), the bind group of a pass's input textures ([`bindings`]), the
//! device objects of a pass that reads them ([`input_pass`]), the recording of passes
//! that draw the scene's meshes ([`scene_draw`]), the opaque draws as compute
//! rasterisers see them ([`raster_draws`]), their triangles binned to tiles
//! ([`tile_bins`], sized by [`bin_sizes`]) and culled by occlusion ([`occlusion`]), groups of storage buffers
//! ([`storage`]), a pass set up with and without its optional shadow atlas
//! ([`shadowed`]) and for the optional textures its plan keeps ([`per_kept`]), and what the
//! atlas's passes remember to keep it ([`shadow_cache`]).
//! Layouts, modules and pipelines are created through [`crate::kept`].

pub(crate) mod bin_sizes;
pub(crate) mod bindings;
pub(crate) mod input_pass;
pub(crate) mod occlusion;
pub(crate) mod per_kept;
pub(crate) mod pipeline;
pub(crate) mod raster_draws;
pub(crate) mod recorder;
pub(crate) mod scene_draw;
pub(crate) mod shadow_cache;
pub(crate) mod shadowed;
pub(crate) mod storage;
pub(crate) mod tile_bins;

pub(crate) use input_pass::{GroupBuffers, InputPass};
pub(crate) use pipeline::{additive, compute_pipeline, PipelineDesc};
pub(crate) use recorder::{Compute, Frame, Recorded, Recorder, Render};

/// geometry.wgsl's `SPLIT_IDS` for a visibility buffer of `format`: rg16uint holds an ID
/// in two halves, r32uint whole.
pub(crate) fn split_ids(format: wgpu::TextureFormat) -> f64 {
    f64::from(u8::from(format == wgpu::TextureFormat::Rg16Uint))
}

/// Workgroups of `group` invocations for `invocations`, at least one, as x by y within
/// the 65,535 a dimension allows: the shaders flatten them back (`group.y *
/// num_workgroups.x + group.x`; bin_triangles.wgsl, shadow_compute.wgsl).
pub(crate) fn workgroup_grid(invocations: u64, group: u32) -> (u32, u32) {
    let groups = invocations.div_ceil(u64::from(group)).max(1);
    let x = groups.min(65_535);
    (x as u32, groups.div_ceil(x) as u32)
}

/// The stencil bit edge pixels carry (seed 000's 0x80): the edge pass marks it, the light
/// passes test it.
pub(crate) const EDGE_STENCIL: u32 = 0x80;
