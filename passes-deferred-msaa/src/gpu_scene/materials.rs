//! Materials on the device: the constants of every material in one storage buffer, and
//! per material a bind group (group 1 of the G-buffer pass) with its base-color texture.

use wgpu::util::DeviceExt;

use super::textures;
use crate::scene::{AlphaMode, Sampler, Scene};

/// `FLAG_LIT` and `FLAG_UNLIT` in common.wgsl.
const FLAG_LIT: u32 = 1;
const FLAG_UNLIT: u32 = 2;

/// `MaterialData` in scene.wgsl.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct MaterialData {
    base_color: [f32; 4],
    emission: [f32; 3],
    alpha_cutoff: f32,
    metallic: f32,
    roughness: f32,
    flags: u32,
    _pad: u32,
}

/// What the G-buffer pass needs to pick a pipeline for a material.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub struct MaterialState {
    /// Back faces are drawn, with the normal flipped (no culling).
    pub double_sided: bool,
    /// Alpha MASK: fragments are discarded below the cutoff.
    pub masked: bool,
}

pub(super) struct Materials {
    pub data: wgpu::Buffer,
    pub states: Vec<MaterialState>,
    pub bind_groups: Vec<wgpu::BindGroup>,
}

/// The layout of a material's bind group: its base-color texture and sampler.
pub(super) fn layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("deferred material"),
        entries: &[
            wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: wgpu::ShaderStages::FRAGMENT,
                ty: wgpu::BindingType::Texture {
                    sample_type: wgpu::TextureSampleType::Float { filterable: true },
                    view_dimension: wgpu::TextureViewDimension::D2,
                    multisampled: false,
                },
                count: None,
            },
            wgpu::BindGroupLayoutEntry {
                binding: 1,
                visibility: wgpu::ShaderStages::FRAGMENT,
                ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
                count: None,
            },
        ],
    })
}

impl Materials {
    pub fn new(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        scene: &Scene,
        layout: &wgpu::BindGroupLayout,
    ) -> Materials {
        let images: Vec<wgpu::TextureView> = scene
            .textures
            .iter()
            .map(|image| textures::upload(device, queue, image))
            .collect();
        let white = textures::white(device, queue);
        let default_sampler = textures::sampler(device, &Sampler::default());
        let mut data = Vec::new();
        let mut states = Vec::new();
        let mut bind_groups = Vec::new();
        for material in &scene.materials {
            let cutoff = match material.alpha_mode {
                AlphaMode::Mask { cutoff } => cutoff,
                AlphaMode::Opaque => 0.0,
            };
            data.push(MaterialData {
                base_color: material.base_color_factor,
                emission: material.emission(),
                alpha_cutoff: cutoff,
                metallic: material.metallic_factor,
                roughness: material.roughness_factor,
                flags: if material.unlit { FLAG_UNLIT } else { FLAG_LIT },
                _pad: 0,
            });
            states.push(MaterialState {
                double_sided: material.double_sided,
                masked: matches!(material.alpha_mode, AlphaMode::Mask { .. }),
            });
            // Scenes guarantee texture indices are in range; a broken one shows white.
            let texture = material
                .base_color_texture
                .and_then(|t| Some((images.get(t.image)?, textures::sampler(device, &t.sampler))));
            let (view, sampler) = match &texture {
                Some((view, sampler)) => (*view, sampler),
                None => (&white, &default_sampler),
            };
            bind_groups.push(device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some(&material.name),
                layout,
                entries: &[
                    wgpu::BindGroupEntry {
                        binding: 0,
                        resource: wgpu::BindingResource::TextureView(view),
                    },
                    wgpu::BindGroupEntry {
                        binding: 1,
                        resource: wgpu::BindingResource::Sampler(sampler),
                    },
                ],
            }));
        }
        // Storage bindings cannot be empty; scenes always have a material, but keep the
        // buffer valid regardless.
        if data.is_empty() {
            data.push(bytemuck::Zeroable::zeroed());
        }
        Materials {
            data: device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("scene materials"),
                contents: bytemuck::cast_slice(&data),
                usage: wgpu::BufferUsages::STORAGE,
            }),
            states,
            bind_groups,
        }
    }
}
