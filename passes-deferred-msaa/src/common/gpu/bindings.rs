//! A pass's textures as one bind group (group 1 of the deferred shaders, render or
//! compute), made again every frame because the pool may lend a slot different memory.

use graph_core::gpu::FrameResources;

use crate::common::textures::{Input, Texels};

pub(crate) struct TextureBindings {
    pub layout: wgpu::BindGroupLayout,
    bindings: Vec<Input>,
}

impl TextureBindings {
    /// The layout for `bindings` as the plan shapes their textures.
    pub fn new(resources: &FrameResources<'_>, bindings: &[Input]) -> TextureBindings {
        let entries: Vec<wgpu::BindGroupLayoutEntry> = bindings
            .iter()
            .map(|b| {
                let shape = resources.shape(b.texture);
                let sampled = |sample_type| wgpu::BindingType::Texture {
                    sample_type,
                    view_dimension: wgpu::TextureViewDimension::D2,
                    multisampled: shape.samples > 1,
                };
                wgpu::BindGroupLayoutEntry {
                    binding: b.binding,
                    visibility: wgpu::ShaderStages::FRAGMENT | wgpu::ShaderStages::COMPUTE,
                    ty: match b.texels {
                        // textureLoad only: nothing is filtered, and r32float is not
                        // filterable.
                        Texels::Float => {
                            sampled(wgpu::TextureSampleType::Float { filterable: false })
                        }
                        Texels::Uint => sampled(wgpu::TextureSampleType::Uint),
                        Texels::Depth => sampled(wgpu::TextureSampleType::Depth),
                        Texels::Store => wgpu::BindingType::StorageTexture {
                            access: wgpu::StorageTextureAccess::WriteOnly,
                            format: shape.format,
                            view_dimension: wgpu::TextureViewDimension::D2,
                        },
                    },
                    count: None,
                }
            })
            .collect();
        let layout = resources
            .device
            .create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some("deferred pass inputs"),
                entries: &entries,
            });
        TextureBindings {
            layout,
            bindings: bindings.to_vec(),
        }
    }

    pub fn bind_group(&self, resources: &FrameResources<'_>) -> wgpu::BindGroup {
        let entries: Vec<wgpu::BindGroupEntry<'_>> = self
            .bindings
            .iter()
            .map(|b| wgpu::BindGroupEntry {
                binding: b.binding,
                resource: wgpu::BindingResource::TextureView(
                    resources.aspect_view(b.texture, b.aspect),
                ),
            })
            .collect();
        resources
            .device
            .create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("deferred pass inputs"),
                layout: &self.layout,
                entries: &entries,
            })
    }
}
