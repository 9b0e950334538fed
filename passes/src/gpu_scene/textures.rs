//! Scene images on the device and the samplers materials use.

use wgpu::util::DeviceExt;
use wgpu::TextureViewDimension::D2;

use rgraph_scene::{FilterMode, Sampler, TextureImage, WrapMode};

/// Uploads one decoded image with its mip chain (scene/src/mips.rs).
pub(super) fn upload(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    image: &TextureImage,
) -> wgpu::TextureView {
    let format = if image.srgb {
        wgpu::TextureFormat::Rgba8UnormSrgb
    } else {
        wgpu::TextureFormat::Rgba8Unorm
    };
    let mut texels = image.rgba8.clone();
    texels.extend(image.mip_chain().into_iter().flatten());
    let size = (image.width, image.height, image.mip_levels());
    create(device, queue, &image.name, size, format, D2, &texels)
}

/// The texture of a material without one of its textures: one white texel (1.0 in every
/// channel, sRGB or not), which multiplies the texture's factor by exactly one, so every
/// material samples the same way.
pub(super) fn white(device: &wgpu::Device, queue: &wgpu::Queue) -> wgpu::TextureView {
    let format = wgpu::TextureFormat::Rgba8UnormSrgb;
    create(device, queue, "white", (1, 1, 1), format, D2, &[255; 4])
}

/// A 2D texture, or a cube map (`dimension` Cube: six layers), of `(width, height, mip
/// levels)` from `texels`: each layer's levels in order, layer after layer.
pub(super) fn create(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    label: &str,
    (width, height, mip_level_count): (u32, u32, u32),
    format: wgpu::TextureFormat,
    dimension: wgpu::TextureViewDimension,
    texels: &[u8],
) -> wgpu::TextureView {
    let layers = match dimension {
        wgpu::TextureViewDimension::Cube => 6,
        _ => 1,
    };
    let size = (width, height, layers, mip_level_count);
    create_layers(device, queue, label, size, format, dimension, texels)
}

/// A texture of `(width, height, layers, mip levels)` seen as `dimension` (D2Array for
/// the texture table's arrays), from `texels` as [`create`] takes them.
pub(super) fn create_layers(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    label: &str,
    (width, height, layers, mip_level_count): (u32, u32, u32, u32),
    format: wgpu::TextureFormat,
    dimension: wgpu::TextureViewDimension,
    texels: &[u8],
) -> wgpu::TextureView {
    device
        .create_texture_with_data(
            queue,
            &wgpu::TextureDescriptor {
                label: Some(label),
                size: wgpu::Extent3d {
                    width,
                    height,
                    depth_or_array_layers: layers,
                },
                mip_level_count,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage: wgpu::TextureUsages::TEXTURE_BINDING,
                view_formats: &[],
            },
            wgpu::util::TextureDataOrder::LayerMajor,
            texels,
        )
        .create_view(&wgpu::TextureViewDescriptor {
            dimension: Some(dimension),
            ..Default::default()
        })
}

/// How a material samples its texture: glTF's sampler, mipmaps included.
pub(super) fn sampler(device: &wgpu::Device, sampler: &Sampler) -> wgpu::Sampler {
    let address = |w: WrapMode| match w {
        WrapMode::Repeat => wgpu::AddressMode::Repeat,
        WrapMode::MirroredRepeat => wgpu::AddressMode::MirrorRepeat,
        WrapMode::ClampToEdge => wgpu::AddressMode::ClampToEdge,
    };
    let filter = |f: FilterMode| match f {
        FilterMode::Nearest => wgpu::FilterMode::Nearest,
        FilterMode::Linear => wgpu::FilterMode::Linear,
    };
    let mip_filter = |f: FilterMode| match f {
        FilterMode::Nearest => wgpu::MipmapFilterMode::Nearest,
        FilterMode::Linear => wgpu::MipmapFilterMode::Linear,
    };
    device.create_sampler(&wgpu::SamplerDescriptor {
        label: None,
        address_mode_u: address(sampler.wrap_u),
        address_mode_v: address(sampler.wrap_v),
        mag_filter: filter(sampler.mag_filter),
        min_filter: filter(sampler.min_filter),
        mipmap_filter: sampler
            .mipmap_filter
            .map_or(wgpu::MipmapFilterMode::Nearest, mip_filter),
        // A glTF minification filter without mipmaps (NEAREST, LINEAR) reads level 0 only.
        lod_max_clamp: match sampler.mipmap_filter {
            Some(_) => 32.0,
            None => 0.0,
        },
        ..Default::default()
    })
}
