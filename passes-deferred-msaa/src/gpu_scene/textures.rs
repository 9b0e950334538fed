//! Scene images on the device and the samplers materials use.

use wgpu::util::DeviceExt;

use crate::scene::{FilterMode, Sampler, TextureImage, WrapMode};

/// Uploads one decoded image (one mip level: minified textures alias, see the crate docs).
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
    create(
        device,
        queue,
        &image.name,
        image.width,
        image.height,
        format,
        &image.rgba8,
    )
}

/// The texture of materials without a base-color texture: one white texel, so every
/// material samples the same way.
pub(super) fn white(device: &wgpu::Device, queue: &wgpu::Queue) -> wgpu::TextureView {
    let format = wgpu::TextureFormat::Rgba8UnormSrgb;
    create(device, queue, "white", 1, 1, format, &[255; 4])
}

fn create(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    label: &str,
    width: u32,
    height: u32,
    format: wgpu::TextureFormat,
    rgba8: &[u8],
) -> wgpu::TextureView {
    device
        .create_texture_with_data(
            queue,
            &wgpu::TextureDescriptor {
                label: Some(label),
                size: wgpu::Extent3d {
                    width,
                    height,
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage: wgpu::TextureUsages::TEXTURE_BINDING,
                view_formats: &[],
            },
            wgpu::util::TextureDataOrder::LayerMajor,
            rgba8,
        )
        .create_view(&wgpu::TextureViewDescriptor::default())
}

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
    device.create_sampler(&wgpu::SamplerDescriptor {
        label: None,
        address_mode_u: address(sampler.wrap_u),
        address_mode_v: address(sampler.wrap_v),
        mag_filter: filter(sampler.mag_filter),
        min_filter: filter(sampler.min_filter),
        ..Default::default()
    })
}
