//! Device-side helpers the deferred plugins share (feature `gpu`): one way to build a
//! render pipeline, a cache of pipelines keyed by what the plan decides at execution
//! (formats, sample counts), the bind group of a pass's input textures, and the
//! recording of full-screen passes.

mod bindings;
pub(crate) mod forward;
pub(crate) mod fullscreen;
pub(crate) mod gbuffer;
pub(crate) mod gbuffer_resolve;
pub(crate) mod light;
mod pipeline;
mod scene_draw;

pub(crate) use bindings::TextureBindings;
use fullscreen::EDGE_STENCIL;
pub(crate) use pipeline::{additive, PipelineDesc, Pipelines};

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
