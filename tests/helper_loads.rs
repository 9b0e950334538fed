//! The minimal repro of lavapipe's texture seams (docs/lavapipe-seams.md) in plain wgpu,
//! no graph: a quad of two triangles over the whole target, textured with a magnified
//! checker whose coarser mip levels are solid red (a red pixel sampled a level the
//! magnified checker never needs), its texture coordinates through an identity transform
//! read from a storage buffer, as material_bound.wgsl reads `materials`.
//!
//! Mesa's llvmpipe 22.3.6 (Debian 12's lavapipe) runs no storage-buffer load for a 2x2
//! quad's helper invocations: they read zero, their coordinates become (0, 0), and
//! implicit derivatives in each quad the diagonal crosses pick the coarsest level. The
//! coordinates' own derivatives through the transform's linear part (`textureSampleGrad`,
//! what material_bound.wgsl does) never read a loaded value in another lane. Run with
//! `--nocapture` to see whether the driver at hand has the bug (Mesa 25.0.7 has not).

use rgraph_core::gpu::read_rgba8;
use wgpu::util::DeviceExt;

use crate::common::{bind_group, gpu, render_pipeline};

const SIZE: u32 = 64;
/// Texels a side of the checker: 4 pixels per texel, levels of detail below 0.
const TEXELS: u32 = 16;
const RED: [u8; 4] = [255, 0, 0, 255];

/// The vertex stage and bindings both fragment stages share.
const COMMON: &str = r#"
struct Transform { m: mat3x2<f32>, pad: vec2<f32> }
@group(0) @binding(0) var checker: texture_2d<f32>;
@group(0) @binding(1) var checker_sampler: sampler;
@group(0) @binding(2) var<storage, read> transforms: array<Transform>;

struct Varyings {
    @builtin(position) clip: vec4<f32>,
    @location(0) uv: vec2<f32>,
}

// Two triangles over the target, split along the diagonal from bottom left to top right.
@vertex
fn vs(@builtin(vertex_index) i: u32) -> Varyings {
    var corners = array<vec2<f32>, 4>(vec2(-1.0, -1.0), vec2(1.0, -1.0), vec2(1.0, 1.0), vec2(-1.0, 1.0));
    var order = array<u32, 6>(0u, 1u, 2u, 0u, 2u, 3u);
    let p = corners[order[i]];
    return Varyings(vec4<f32>(p, 0.5, 1.0), p * 0.5 + 0.5);
}

fn transformed(uv: vec2<f32>) -> vec2<f32> {
    return transforms[0].m * vec3<f32>(uv, 1.0);
}
"#;

/// Implicit derivatives of the transformed coordinates.
const IMPLICIT: &str = r#"
@fragment
fn fs(in: Varyings) -> @location(0) vec4<f32> {
    return textureSample(checker, checker_sampler, transformed(in.uv));
}
"#;

/// The interpolated coordinates' derivatives through the transform's linear part.
const EXPLICIT: &str = r#"
@fragment
fn fs(in: Varyings) -> @location(0) vec4<f32> {
    let t = transforms[0].m;
    let linear = mat2x2<f32>(t[0], t[1]);
    return textureSampleGrad(checker, checker_sampler, transformed(in.uv), linear * dpdx(in.uv), linear * dpdy(in.uv));
}
"#;

/// The quad drawn with fragment stage `fs` at `samples` per pixel, resolved.
fn draw(fs: &str, samples: u32) -> Vec<[u8; 4]> {
    let gpu = gpu();
    let (device, queue) = (&gpu.device, &gpu.queue);
    let format = wgpu::TextureFormat::Rgba8Unorm;
    let levels = TEXELS.ilog2() + 1;
    let texels: Vec<u8> = (0..levels)
        .flat_map(|level| {
            let side = TEXELS >> level;
            (0..side * side).flat_map(move |i| match (level, (i % side + i / side) % 2) {
                (0, 0) => [0, 0, 0, 255],
                (0, _) => [255; 4],
                _ => RED,
            })
        })
        .collect();
    let checker = device.create_texture_with_data(
        queue,
        &wgpu::TextureDescriptor {
            label: Some("checker"),
            size: wgpu::Extent3d {
                width: TEXELS,
                height: TEXELS,
                depth_or_array_layers: 1,
            },
            mip_level_count: levels,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage: wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        },
        wgpu::util::TextureDataOrder::LayerMajor,
        &texels,
    );
    let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
        address_mode_u: wgpu::AddressMode::Repeat,
        address_mode_v: wgpu::AddressMode::Repeat,
        mipmap_filter: wgpu::MipmapFilterMode::Nearest,
        ..Default::default()
    });
    let identity: Vec<u8> = [1.0f32, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0]
        .iter()
        .flat_map(|v| v.to_le_bytes())
        .collect();
    let transforms = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("transforms"),
        contents: &identity,
        usage: wgpu::BufferUsages::STORAGE,
    });
    let pipeline = render_pipeline(device, &format!("{COMMON}{fs}"), format, samples);
    let view = checker.create_view(&Default::default());
    let bindings = bind_group(
        device,
        &pipeline.get_bind_group_layout(0),
        &[
            wgpu::BindingResource::TextureView(&view),
            wgpu::BindingResource::Sampler(&sampler),
            transforms.as_entire_binding(),
        ],
    );
    let target = |samples: u32, usage: wgpu::TextureUsages| {
        device.create_texture(&wgpu::TextureDescriptor {
            label: Some("quad"),
            size: wgpu::Extent3d {
                width: SIZE,
                height: SIZE,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: samples,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT | usage,
            view_formats: &[],
        })
    };
    let resolved = target(1, wgpu::TextureUsages::COPY_SRC);
    let multisampled = (samples > 1).then(|| target(samples, wgpu::TextureUsages::empty()));
    let resolved_view = resolved.create_view(&Default::default());
    let multisampled_view = multisampled.map(|t| t.create_view(&Default::default()));
    let mut encoder = device.create_command_encoder(&Default::default());
    {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("quad"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: multisampled_view.as_ref().unwrap_or(&resolved_view),
                depth_slice: None,
                resolve_target: multisampled_view.as_ref().map(|_| &resolved_view),
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: None,
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_pipeline(&pipeline);
        pass.set_bind_group(0, &bindings, &[]);
        pass.draw(0..6, 0..1);
    }
    queue.submit([encoder.finish()]);
    read_rgba8(device, queue, &resolved).unwrap_or_else(|e| panic!("{e}"))
}

/// Pixels neither black nor white: they sampled a coarser level than the checker's.
fn off_level(pixels: &[[u8; 4]]) -> usize {
    let level_0 = |p: &&[u8; 4]| p[..3].iter().all(|&c| c <= 2) || p[..3].iter().all(|&c| c >= 253);
    pixels.iter().filter(|p| !level_0(p)).count()
}

/// Derivatives of the interpolated coordinates through the transform's linear part
/// sample the magnified checker everywhere, at 1x and 4x; implicit derivatives of the
/// transformed coordinates are reported, per driver.
#[test]
fn derivatives_of_interpolated_coordinates_never_read_a_helper_lane_s_loads() {
    let driver = gpu().info.driver_info.clone();
    for samples in [1, 4] {
        let explicit = off_level(&draw(EXPLICIT, samples));
        assert_eq!(
            explicit, 0,
            "{driver}, {samples}x: {explicit} pixels sampled a coarser level with derivatives \
             of the interpolated coordinates"
        );
        let implicit = off_level(&draw(IMPLICIT, samples));
        eprintln!(
            "{driver}, {samples}x: implicit derivatives of coordinates through a \
             storage-buffer transform: {implicit} of {} pixels off the checker's level{}",
            SIZE * SIZE,
            match implicit {
                0 => " (helper invocations run storage loads)",
                _ => " (helper invocations read zero: the seam)",
            }
        );
    }
}
