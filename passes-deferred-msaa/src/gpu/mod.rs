//! Device-side helpers the deferred plugins share (feature `gpu`): one way to build a
//! render pipeline, a cache of pipelines keyed by what the plan decides at execution
//! (formats, sample counts), the bind group of a pass's input textures, and the
//! recording of full-screen passes.

pub(crate) mod auto_exposure;
mod bindings;
pub(crate) mod forward;
pub(crate) mod fullscreen;
pub(crate) mod gbuffer;
pub(crate) mod gbuffer_resolve;
mod input_pass;
pub(crate) mod light;
pub(crate) mod light_tiled;
mod pipeline;
mod scene_draw;

use std::sync::Arc;

use crate::gpu_scene::GpuScene;
pub(crate) use bindings::TextureBindings;
use fullscreen::EDGE_STENCIL;
use input_pass::InputPass;
pub(crate) use pipeline::{additive, PipelineDesc, Pipelines};

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

pub(crate) fn module(device: &wgpu::Device, label: &str, wgsl: &str) -> wgpu::ShaderModule {
    device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(label),
        source: wgpu::ShaderSource::Wgsl(wgsl.into()),
    })
}

/// A pipeline layout of `groups` in order; `None` leaves a group unused.
pub(crate) fn pipeline_layout(
    device: &wgpu::Device,
    groups: &[Option<&wgpu::BindGroupLayout>],
) -> wgpu::PipelineLayout {
    device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: None,
        bind_group_layouts: groups,
        immediate_size: 0,
    })
}
