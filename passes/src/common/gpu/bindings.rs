//! A pass's textures as one bind group (group 1 of the deferred shaders, render or
//! compute), made again every frame because the pool may lend a slot different memory,
//! with the sampler of any input read filtered (linear) or gathered (nearest) and any
//! storage buffers it reads.

use rgraph_core::gpu::FrameResources;
use rgraph_core::BufferHandle;

use crate::common::textures::{Input, Texels};

pub(crate) struct TextureBindings {
    pub layout: wgpu::BindGroupLayout,
    bindings: Vec<Input>,
    /// Graph buffers read as read-only storage, by binding.
    buffers: Vec<(u32, BufferHandle)>,
    /// Bindings of read-write storage buffers the pass owns (given to
    /// [`bind_group_with`](Self::bind_group_with)).
    owned: Vec<u32>,
    /// The clamp-to-edge samplers the inputs are read through, with their bindings:
    /// linear for `Texels::Filtered`, nearest for `Texels::Gathered`.
    samplers: Vec<(u32, wgpu::Sampler)>,
}

/// A sampler binding of `bindings`' inputs: its binding, and whether it filters.
fn samplers(bindings: &[Input]) -> impl Iterator<Item = (u32, bool)> + '_ {
    bindings.iter().filter_map(|b| match b.texels {
        Texels::Filtered { sampler } => Some((sampler, true)),
        Texels::Gathered { sampler } => Some((sampler, false)),
        _ => None,
    })
}

impl TextureBindings {
    /// The layout for `bindings` as the plan shapes their textures.
    pub fn new(resources: &FrameResources<'_>, bindings: &[Input]) -> TextureBindings {
        Self::with_buffers(resources, bindings, &[], &[])
    }

    /// [`new`](Self::new), read-only storage `buffers` at their bindings, and read-write
    /// storage buffers the pass owns at bindings `owned`.
    pub fn with_buffers(
        resources: &FrameResources<'_>,
        bindings: &[Input],
        buffers: &[(u32, BufferHandle)],
        owned: &[u32],
    ) -> TextureBindings {
        let visibility = wgpu::ShaderStages::FRAGMENT | wgpu::ShaderStages::COMPUTE;
        let mut entries: Vec<wgpu::BindGroupLayoutEntry> = bindings
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
                    visibility,
                    ty: match b.texels {
                        // textureLoad or textureGather: nothing is filtered, and
                        // r32float is not filterable.
                        Texels::Float | Texels::Gathered { .. } => {
                            sampled(wgpu::TextureSampleType::Float { filterable: false })
                        }
                        Texels::Filtered { .. } => {
                            sampled(wgpu::TextureSampleType::Float { filterable: true })
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
        // Graph buffers read only, then the pass's own buffers read and written.
        let storage = (buffers.iter().map(|&(binding, _)| (binding, true)))
            .chain(owned.iter().map(|&binding| (binding, false)));
        entries.extend(
            storage.map(|(binding, read_only)| wgpu::BindGroupLayoutEntry {
                binding,
                visibility,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Storage { read_only },
                    has_dynamic_offset: false,
                    min_binding_size: None,
                },
                count: None,
            }),
        );
        entries.extend(
            samplers(bindings).map(|(binding, filtering)| wgpu::BindGroupLayoutEntry {
                binding,
                visibility,
                ty: wgpu::BindingType::Sampler(match filtering {
                    true => wgpu::SamplerBindingType::Filtering,
                    false => wgpu::SamplerBindingType::NonFiltering,
                }),
                count: None,
            }),
        );
        let samplers = samplers(bindings)
            .map(|(binding, filtering)| {
                let (label, filter) = match filtering {
                    true => ("deferred pass inputs (linear)", wgpu::FilterMode::Linear),
                    false => ("deferred pass inputs (gathered)", wgpu::FilterMode::Nearest),
                };
                let sampler = resources.device.create_sampler(&wgpu::SamplerDescriptor {
                    label: Some(label),
                    mag_filter: filter,
                    min_filter: filter,
                    ..Default::default()
                });
                (binding, sampler)
            })
            .collect();
        let layout =
            crate::kept::bind_group_layout(resources.device, "deferred pass inputs", &entries);
        TextureBindings {
            layout,
            bindings: bindings.to_vec(),
            buffers: buffers.to_vec(),
            owned: owned.to_vec(),
            samplers,
        }
    }

    pub fn bind_group(&self, resources: &FrameResources<'_>) -> wgpu::BindGroup {
        self.bind_group_with(resources, &[])
    }

    /// The group with `owned` bound at the bindings given when the layout was made, in
    /// that order.
    pub fn bind_group_with(
        &self,
        resources: &FrameResources<'_>,
        owned: &[&wgpu::Buffer],
    ) -> wgpu::BindGroup {
        let mut entries: Vec<wgpu::BindGroupEntry<'_>> = self
            .bindings
            .iter()
            .map(|b| wgpu::BindGroupEntry {
                binding: b.binding,
                resource: wgpu::BindingResource::TextureView(
                    resources.aspect_view(b.texture, b.aspect),
                ),
            })
            .collect();
        entries.extend(
            self.buffers
                .iter()
                .map(|&(binding, buffer)| wgpu::BindGroupEntry {
                    binding,
                    resource: resources.buffer(buffer).as_entire_binding(),
                }),
        );
        entries.extend(self.owned.iter().zip(owned).map(|(&binding, buffer)| {
            wgpu::BindGroupEntry {
                binding,
                resource: buffer.as_entire_binding(),
            }
        }));
        entries.extend(
            (self.samplers.iter()).map(|(binding, sampler)| wgpu::BindGroupEntry {
                binding: *binding,
                resource: wgpu::BindingResource::Sampler(sampler),
            }),
        );
        resources
            .device
            .create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("deferred pass inputs"),
                layout: &self.layout,
                entries: &entries,
            })
    }
}
