//! Device objects the shader plugins share (feature `gpu`): bind group layouts from the
//! checked bindings, the samplers and uniform buffers the plugins own, and the bind
//! groups made each frame (the pool may lend a slot's texture different memory).

use wgpu::util::DeviceExt;

use super::binding::{Bound, Filter, Source};
use crate::access::Aspect;
use crate::handle::{BufferHandle, TextureHandle};
use crate::record::FrameResources;

/// The bindings of one pass on one device.
pub(crate) struct GpuBindings {
    layouts: Vec<wgpu::BindGroupLayout>,
    /// (group, binding, what is bound there), in group and binding order.
    entries: Vec<(u32, u32, Object)>,
}

enum Object {
    Texture(TextureHandle, Aspect),
    Buffer(BufferHandle),
    Sampler(wgpu::Sampler),
    Uniform(wgpu::Buffer),
}

impl GpuBindings {
    /// Layouts for groups 0 up to the highest group bound (empty where a group has no
    /// binding), visible to `visibility`, and the objects the plugin owns.
    pub fn new(device: &wgpu::Device, bound: &[Bound], visibility: wgpu::ShaderStages) -> Self {
        let groups = bound.iter().map(|b| b.group + 1).max().unwrap_or(0);
        let layouts = (0..groups)
            .map(|group| {
                let entries: Vec<wgpu::BindGroupLayoutEntry> = bound
                    .iter()
                    .filter(|b| b.group == group)
                    .map(|b| wgpu::BindGroupLayoutEntry {
                        binding: b.binding,
                        visibility,
                        ty: b.ty,
                        count: None,
                    })
                    .collect();
                device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                    label: None,
                    entries: &entries,
                })
            })
            .collect();
        let entries = bound
            .iter()
            .map(|b| (b.group, b.binding, Object::new(device, &b.source)))
            .collect();
        GpuBindings { layouts, entries }
    }

    pub fn pipeline_layout(&self, device: &wgpu::Device) -> wgpu::PipelineLayout {
        let layouts: Vec<Option<&wgpu::BindGroupLayout>> = self.layouts.iter().map(Some).collect();
        device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: None,
            bind_group_layouts: &layouts,
            immediate_size: 0,
        })
    }

    /// This frame's bind groups, by group index.
    pub fn bind_groups(&self, resources: &FrameResources<'_>) -> Vec<wgpu::BindGroup> {
        self.layouts
            .iter()
            .zip(0u32..)
            .map(|(layout, group)| {
                let entries: Vec<wgpu::BindGroupEntry<'_>> = self
                    .entries
                    .iter()
                    .filter(|(g, _, _)| *g == group)
                    .map(|(_, binding, object)| wgpu::BindGroupEntry {
                        binding: *binding,
                        resource: object.resource(resources),
                    })
                    .collect();
                resources
                    .device
                    .create_bind_group(&wgpu::BindGroupDescriptor {
                        label: None,
                        layout,
                        entries: &entries,
                    })
            })
            .collect()
    }
}

impl Object {
    fn new(device: &wgpu::Device, source: &Source) -> Object {
        match source {
            Source::Texture(handle, aspect) => Object::Texture(*handle, *aspect),
            Source::Buffer(handle) => Object::Buffer(*handle),
            Source::Sampler(filter) => {
                let mode = match filter {
                    Filter::Linear => wgpu::FilterMode::Linear,
                    Filter::Nearest => wgpu::FilterMode::Nearest,
                };
                Object::Sampler(device.create_sampler(&wgpu::SamplerDescriptor {
                    mag_filter: mode,
                    min_filter: mode,
                    ..Default::default()
                }))
            }
            Source::Uniform(bytes) => Object::Uniform(device.create_buffer_init(
                &wgpu::util::BufferInitDescriptor {
                    label: None,
                    contents: bytes,
                    usage: wgpu::BufferUsages::UNIFORM,
                },
            )),
        }
    }

    fn resource<'a>(&'a self, resources: &FrameResources<'a>) -> wgpu::BindingResource<'a> {
        match self {
            Object::Texture(handle, aspect) => {
                wgpu::BindingResource::TextureView(resources.aspect_view(*handle, *aspect))
            }
            Object::Buffer(handle) => resources.buffer(*handle).as_entire_binding(),
            Object::Sampler(sampler) => wgpu::BindingResource::Sampler(sampler),
            Object::Uniform(buffer) => buffer.as_entire_binding(),
        }
    }
}

/// A shader module from WGSL that naga already validated when the graph loaded.
pub(crate) fn module(device: &wgpu::Device, wgsl: &str) -> wgpu::ShaderModule {
    device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: None,
        source: wgpu::ShaderSource::Wgsl(wgsl.into()),
    })
}
