//! The scene's bind group (group 0 of every deferred pass that reads the scene, render
//! or compute), as scene.wgsl and lighting.wgsl declare it: camera, meshes, materials,
//! lights and light info at bindings 0 to 4, the environment's prefiltered cube map, its
//! sampler and the split-sum lookup table at 5 to 7, the shadow views at 8 (shadow.wgsl).

use super::environment::EnvironmentMaps;
use super::shadows::ShadowBuffers;

pub(super) fn scene_layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
    let entry = |binding, ty| wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::VERTEX_FRAGMENT | wgpu::ShaderStages::COMPUTE,
        ty,
        count: None,
    };
    let uniform = wgpu::BindingType::Buffer {
        ty: wgpu::BufferBindingType::Uniform,
        has_dynamic_offset: false,
        min_binding_size: None,
    };
    let storage = wgpu::BindingType::Buffer {
        ty: wgpu::BufferBindingType::Storage { read_only: true },
        has_dynamic_offset: false,
        min_binding_size: None,
    };
    let texture = |view_dimension| wgpu::BindingType::Texture {
        sample_type: wgpu::TextureSampleType::Float { filterable: true },
        view_dimension,
        multisampled: false,
    };
    crate::kept::bind_group_layout(
        device,
        "deferred scene",
        &[
            entry(0, uniform),
            entry(1, storage),
            entry(2, storage),
            entry(3, storage),
            entry(4, uniform),
            entry(5, texture(wgpu::TextureViewDimension::Cube)),
            entry(
                6,
                wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
            ),
            entry(7, texture(wgpu::TextureViewDimension::D2)),
            entry(8, uniform),
        ],
    )
}

pub(super) fn scene_group(
    device: &wgpu::Device,
    layout: &wgpu::BindGroupLayout,
    buffers: [&wgpu::Buffer; 5],
    environment: &EnvironmentMaps,
    shadows: &ShadowBuffers,
) -> wgpu::BindGroup {
    let mut entries: Vec<wgpu::BindGroupEntry<'_>> = buffers
        .iter()
        .zip(0u32..)
        .map(|(buffer, binding)| wgpu::BindGroupEntry {
            binding,
            resource: buffer.as_entire_binding(),
        })
        .collect();
    entries.extend([
        wgpu::BindGroupEntry {
            binding: 5,
            resource: wgpu::BindingResource::TextureView(&environment.cube),
        },
        wgpu::BindGroupEntry {
            binding: 6,
            resource: wgpu::BindingResource::Sampler(&environment.sampler),
        },
        wgpu::BindGroupEntry {
            binding: 7,
            resource: wgpu::BindingResource::TextureView(&environment.lut),
        },
        wgpu::BindGroupEntry {
            binding: 8,
            resource: shadows.views.as_entire_binding(),
        },
    ]);
    device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("deferred scene"),
        layout,
        entries: &entries,
    })
}
