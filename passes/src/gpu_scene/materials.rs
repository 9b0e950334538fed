//! Materials on the device: the constants of every material in one storage buffer, and
//! per material a bind group (group 1 of the G-buffer and forward passes,
//! material_bound.wgsl) with its textures, made when a pass first draws with them.

use std::collections::HashMap;
use std::sync::OnceLock;

use wgpu::util::DeviceExt;

use super::textures;
use rgraph_scene::{dielectric_f0, AlphaMode, Material, Sampler, Scene, TextureRef};

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
    normal_scale: f32,
    occlusion_strength: f32,
    /// Bit `slot` set: the texture of that slot samples TEXCOORD_1.
    uv_sets: u32,
    _pad: [u32; 2],
    specular_f0: [f32; 3],
    specular: f32,
    sheen_color: [f32; 3],
    sheen_roughness: f32,
    clearcoat: f32,
    clearcoat_roughness: f32,
    clearcoat_normal_scale: f32,
    _pad2: u32,
    /// Per slot, KHR_texture_transform's matrix (`mat3x2<f32>`, three columns).
    uv_transforms: [[[f32; 2]; 3]; TEXTURE_SLOTS as usize],
}

/// What a scene-drawing pass needs to pick a pipeline for a material, and which pass
/// draws it.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub struct MaterialState {
    /// Back faces are drawn, with the normal flipped (no culling).
    pub double_sided: bool,
    /// Alpha MASK: fragments are discarded below the cutoff.
    pub masked: bool,
    /// Alpha BLEND: drawn by the transparent pass only, never by the opaque ones.
    pub blended: bool,
}

pub(super) struct Materials {
    pub data: wgpu::Buffer,
    pub states: Vec<MaterialState>,
    bind_groups: OnceLock<Vec<wgpu::BindGroup>>,
}

/// A material's textures in binding order (material_bound.wgsl):
/// [`rgraph_scene::Material::texture_slots`].
const TEXTURE_SLOTS: u32 = rgraph_scene::TEXTURE_SLOTS as u32;

/// The layout of a material's bind group: per texture of [`TEXTURE_SLOTS`], the texture
/// (binding `2 * slot`) and its sampler (binding `2 * slot + 1`).
pub(super) fn layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
    let entries: Vec<wgpu::BindGroupLayoutEntry> = (0..TEXTURE_SLOTS)
        .flat_map(|slot| {
            [
                wgpu::BindGroupLayoutEntry {
                    binding: 2 * slot,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Float { filterable: true },
                        view_dimension: wgpu::TextureViewDimension::D2,
                        multisampled: false,
                    },
                    count: None,
                },
                wgpu::BindGroupLayoutEntry {
                    binding: 2 * slot + 1,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
                    count: None,
                },
            ]
        })
        .collect();
    crate::kept::bind_group_layout(device, "deferred material", &entries)
}

impl Materials {
    /// The constants and pipeline states of `scene`'s materials; their textures wait for
    /// [`bind_groups`](Self::bind_groups).
    pub fn new(device: &wgpu::Device, scene: &Scene) -> Materials {
        let mut data: Vec<MaterialData> = scene.materials.iter().map(material_data).collect();
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
            states: scene
                .materials
                .iter()
                .map(|material| MaterialState {
                    double_sided: material.double_sided,
                    masked: matches!(material.alpha_mode, AlphaMode::Mask { .. }),
                    blended: material.alpha_mode == AlphaMode::Blend,
                })
                .collect(),
            bind_groups: OnceLock::new(),
        }
    }

    /// Per material of `scene` (this upload's) its bind group of `layout`, its images
    /// uploaded the first time: passes that bind textures per draw pay for them, and a
    /// visibility buffer's shading, which reads the texture table, does not.
    pub fn bind_groups(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        scene: &Scene,
        layout: &wgpu::BindGroupLayout,
    ) -> &[wgpu::BindGroup] {
        self.bind_groups
            .get_or_init(|| bind_groups(device, queue, scene, layout))
    }
}

/// `material`'s constants.
fn material_data(material: &Material) -> MaterialData {
    let cutoff = match material.alpha_mode {
        AlphaMode::Mask { cutoff } => cutoff,
        AlphaMode::Opaque | AlphaMode::Blend => 0.0,
    };
    // An unlit material's layers would shade nothing: the core model's keep the
    // features (Material::has_clearcoat, ...) and the data in step.
    let plain = Material::gltf_default();
    let layered = if material.unlit { &plain } else { material };
    MaterialData {
        base_color: material.base_color_factor,
        emission: material.emission(),
        alpha_cutoff: cutoff,
        metallic: material.metallic_factor,
        roughness: material.roughness_factor,
        flags: if material.unlit { FLAG_UNLIT } else { FLAG_LIT },
        normal_scale: match material.normal_texture {
            Some(_) => material.normal_scale,
            None => 0.0,
        },
        occlusion_strength: match material.occlusion_texture {
            Some(_) => material.occlusion_strength,
            None => 0.0,
        },
        uv_sets: (0u32..)
            .zip(material.texture_slots())
            .filter(|(_, t)| t.is_some_and(|t| t.tex_coord == 1))
            .fold(0, |bits, (slot, _)| bits | 1 << slot),
        _pad: [0; 2],
        specular_f0: layered
            .specular
            .color_factor
            .map(|c| dielectric_f0(layered.ior) * c),
        specular: layered.specular.factor,
        sheen_color: layered.sheen.color_factor,
        sheen_roughness: layered.sheen.roughness_factor,
        clearcoat: layered.clearcoat.factor,
        clearcoat_roughness: layered.clearcoat.roughness_factor,
        clearcoat_normal_scale: match layered.clearcoat.normal_texture {
            Some(_) => layered.clearcoat.normal_scale,
            None => 0.0,
        },
        _pad2: 0,
        uv_transforms: material
            .texture_slots()
            .map(|t| t.map_or(TextureRef::IDENTITY_UV, |t| t.uv_transform)),
    }
}

/// Per material of `scene`, its textures and samplers as a bind group of `layout`.
fn bind_groups(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    scene: &Scene,
    layout: &wgpu::BindGroupLayout,
) -> Vec<wgpu::BindGroup> {
    let images: Vec<wgpu::TextureView> = scene
        .textures
        .iter()
        .map(|image| textures::upload(device, queue, image))
        .collect();
    let white = textures::white(device, queue);
    // One device sampler per distinct glTF sampler: materials share most of them.
    let mut samplers = HashMap::new();
    scene
        .materials
        .iter()
        .map(|material| {
            // Scenes guarantee texture indices are in range; a broken one shows white.
            let textures: Vec<(&wgpu::TextureView, wgpu::Sampler)> = material
                .texture_slots()
                .into_iter()
                .map(|texture| {
                    let (view, sampler) = texture
                        .and_then(|t| Some((images.get(t.image)?, t.sampler)))
                        .unwrap_or((&white, Sampler::default()));
                    let sampler = samplers
                        .entry(sampler)
                        .or_insert_with(|| textures::sampler(device, &sampler));
                    (view, sampler.clone())
                })
                .collect();
            let entries: Vec<wgpu::BindGroupEntry> = (0u32..)
                .zip(&textures)
                .flat_map(|(slot, (view, sampler))| {
                    [
                        wgpu::BindGroupEntry {
                            binding: 2 * slot,
                            resource: wgpu::BindingResource::TextureView(view),
                        },
                        wgpu::BindGroupEntry {
                            binding: 2 * slot + 1,
                            resource: wgpu::BindingResource::Sampler(sampler),
                        },
                    ]
                })
                .collect();
            device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some(&material.name),
                layout,
                entries: &entries,
            })
        })
        .collect()
}
