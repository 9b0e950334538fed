//! The scene's texture table on the device (group 3 of the visibility buffer's shading,
//! material_table.wgsl): the two layer arrays of [`TextureTable`], per material one word
//! per texture slot saying which layer and how its glTF sampler samples it, and eight
//! samplers (repeating or clamping x nearest or linear texels x nearest or linear mips:
//! the shader applies mirroring, and wrap modes that differ between the axes, to the
//! coordinates). Made on first use, so scenes drawn only through G-buffers never pay its
//! memory.

use std::sync::OnceLock;

use wgpu::util::DeviceExt;

use super::textures;
use rgraph_scene::texture_table::{TableArray, TextureTable};
use rgraph_scene::{FilterMode, Scene, TextureRef, WrapMode, TEXTURE_SLOTS};

/// material_table.wgsl's `NO_LAYER`.
const NO_LAYER: u32 = 0xffff;

pub(super) struct TextureTableGpu {
    layout: wgpu::BindGroupLayout,
    group: OnceLock<Result<wgpu::BindGroup, String>>,
}

/// The address mode, texel filter and mipmap filter of the eight samplers, in binding order
/// from 3 (material_table.wgsl).
const SAMPLERS: [(wgpu::AddressMode, wgpu::FilterMode, wgpu::MipmapFilterMode); 8] = {
    use wgpu::AddressMode::{ClampToEdge, Repeat};
    use wgpu::FilterMode::{Linear, Nearest};
    use wgpu::MipmapFilterMode as Mip;
    [
        (Repeat, Nearest, Mip::Nearest),
        (Repeat, Nearest, Mip::Linear),
        (Repeat, Linear, Mip::Nearest),
        (Repeat, Linear, Mip::Linear),
        (ClampToEdge, Nearest, Mip::Nearest),
        (ClampToEdge, Nearest, Mip::Linear),
        (ClampToEdge, Linear, Mip::Nearest),
        (ClampToEdge, Linear, Mip::Linear),
    ]
};

impl TextureTableGpu {
    pub fn new(device: &wgpu::Device) -> TextureTableGpu {
        // The visibility buffer's shading and compute raster read it, and the hardware
        // raster's alpha MASK test (a fragment stage).
        let entry = |binding, ty| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::COMPUTE | wgpu::ShaderStages::FRAGMENT,
            ty,
            count: None,
        };
        let layers = wgpu::BindingType::Texture {
            sample_type: wgpu::TextureSampleType::Float { filterable: true },
            view_dimension: wgpu::TextureViewDimension::D2Array,
            multisampled: false,
        };
        let mut entries = vec![
            entry(
                0,
                wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Storage { read_only: true },
                    has_dynamic_offset: false,
                    min_binding_size: None,
                },
            ),
            entry(1, layers),
            entry(2, layers),
        ];
        entries.extend((3..).zip(SAMPLERS).map(|(binding, _)| {
            entry(
                binding,
                wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
            )
        }));
        TextureTableGpu {
            layout: crate::kept::bind_group_layout(device, "scene texture table", &entries),
            group: OnceLock::new(),
        }
    }

    pub fn layout(&self) -> &wgpu::BindGroupLayout {
        &self.layout
    }

    /// The bind group of `scene`'s table, made the first time; or why the device cannot
    /// hold it (its layer count, size or memory: [`TextureTable::check`] against the
    /// device's limits).
    pub fn group(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        scene: &Scene,
    ) -> Result<&wgpu::BindGroup, &str> {
        let group = self.group.get_or_init(|| self.build(device, queue, scene));
        group.as_ref().map_err(String::as_str)
    }

    fn build(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        scene: &Scene,
    ) -> Result<wgpu::BindGroup, String> {
        let table = TextureTable::of(scene);
        let limits = device.limits();
        let (layers, side) = (
            limits.max_texture_array_layers,
            limits.max_texture_dimension_2d,
        );
        table.check(scene, layers, side).map_err(|e| {
            format!(
                "{e}: a visibility buffer cannot shade the scene's textures; use a G-buffer \
                 pipeline"
            )
        })?;
        let upload = |name, array, format| upload(device, queue, scene, (name, array, format));
        let color = upload(
            "texture table: color",
            &table.color,
            wgpu::TextureFormat::Rgba8UnormSrgb,
        );
        let data = upload(
            "texture table: data",
            &table.data,
            wgpu::TextureFormat::Rgba8Unorm,
        );
        let mut words: Vec<[u32; TEXTURE_SLOTS]> = scene
            .materials
            .iter()
            .map(|m| m.texture_slots().map(|t| slot_word(&table, t)))
            .collect();
        // Storage bindings cannot be empty.
        if words.is_empty() {
            words.push([NO_LAYER; TEXTURE_SLOTS]);
        }
        let slots = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("texture table: material slots"),
            contents: bytemuck::cast_slice(&words),
            usage: wgpu::BufferUsages::STORAGE,
        });
        let samplers: Vec<wgpu::Sampler> = SAMPLERS
            .iter()
            .map(|&(address, filter, mipmap_filter)| {
                device.create_sampler(&wgpu::SamplerDescriptor {
                    label: Some("texture table"),
                    address_mode_u: address,
                    address_mode_v: address,
                    mag_filter: filter,
                    min_filter: filter,
                    mipmap_filter,
                    ..Default::default()
                })
            })
            .collect();
        let mut entries = vec![
            wgpu::BindGroupEntry {
                binding: 0,
                resource: slots.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: wgpu::BindingResource::TextureView(&color),
            },
            wgpu::BindGroupEntry {
                binding: 2,
                resource: wgpu::BindingResource::TextureView(&data),
            },
        ];
        entries.extend(
            (3..)
                .zip(&samplers)
                .map(|(binding, sampler)| wgpu::BindGroupEntry {
                    binding,
                    resource: wgpu::BindingResource::Sampler(sampler),
                }),
        );
        Ok(device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("scene texture table"),
            layout: &self.layout,
            entries: &entries,
        }))
    }
}

/// One array of the table as a 2D array texture of `format`, its layers the images of
/// `scene` it names, with their mips.
fn upload(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    scene: &Scene,
    (name, array, format): (&str, &TableArray, wgpu::TextureFormat),
) -> wgpu::TextureView {
    let size = (
        array.width,
        array.height,
        array.layers(),
        array.mip_levels(),
    );
    let texels = array.texels(&scene.textures);
    let dimension = wgpu::TextureViewDimension::D2Array;
    textures::create_layers(device, queue, name, size, format, dimension, &texels)
}

/// material_table.wgsl's word for a slot holding `texture`: its layer (`NO_LAYER` without
/// one, or for an image index out of range, which the G-buffer path shows white too),
/// array, wrap modes and filters.
fn slot_word(table: &TextureTable, texture: Option<TextureRef>) -> u32 {
    let Some((texture, (color, layer))) = texture.and_then(|t| Some((t, table.layer_of(t.image)?)))
    else {
        return NO_LAYER;
    };
    let wrap = |w| match w {
        WrapMode::Repeat => 0,
        WrapMode::MirroredRepeat => 1,
        WrapMode::ClampToEdge => 2,
    };
    let linear = |f| u32::from(f == FilterMode::Linear);
    let s = texture.sampler;
    let mip = match s.mipmap_filter {
        None => 0,
        Some(FilterMode::Nearest) => 1,
        Some(FilterMode::Linear) => 2,
    };
    layer
        | u32::from(color) << 16
        | wrap(s.wrap_u) << 17
        | wrap(s.wrap_v) << 19
        | linear(s.mag_filter) << 21
        | linear(s.min_filter) << 22
        | mip << 23
}
