//! Every sample of a multisampled float texture, read without resolving: a compute pass
//! copies each sample's `textureLoad` into a storage buffer, which is read back. Works for
//! any float format (rgba16float, rg16float, r32float...; missing channels read as the
//! format's defaults), multisampled or not.

use rgraph_core::gpu::{read_buffer, Gpu};

use super::Frame;

const SHADER: &str = r#"
@group(0) @binding(0) var t: TEX;
@group(0) @binding(1) var<storage, read_write> out: array<vec4<f32>>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(t);
    if id.x >= size.x || id.y >= size.y {
        return;
    }
    let n = COUNT;
    for (var s = 0u; s < n; s++) {
        out[(id.y * size.x + id.x) * n + s] = textureLoad(t, vec2<i32>(id.xy), LOAD);
    }
}
"#;

/// Per pixel (row-major), per sample: the texel as `vec4<f32>`.
pub fn read_samples(gpu: &Gpu, texture: &wgpu::Texture) -> Vec<Vec<[f32; 4]>> {
    let device = &gpu.device;
    let samples = texture.sample_count();
    let multisampled = samples > 1;
    let source = if multisampled {
        SHADER
            .replace("TEX", "texture_multisampled_2d<f32>")
            .replace("COUNT", "textureNumSamples(t)")
            .replace("LOAD", "i32(s)")
    } else {
        SHADER
            .replace("TEX", "texture_2d<f32>")
            .replace("COUNT", "1u")
            .replace("LOAD", "0")
    };
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("read samples"),
        source: wgpu::ShaderSource::Wgsl(source.into()),
    });
    let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("read samples"),
        entries: &[
            wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: wgpu::ShaderStages::COMPUTE,
                ty: wgpu::BindingType::Texture {
                    sample_type: wgpu::TextureSampleType::Float { filterable: false },
                    view_dimension: wgpu::TextureViewDimension::D2,
                    multisampled,
                },
                count: None,
            },
            wgpu::BindGroupLayoutEntry {
                binding: 1,
                visibility: wgpu::ShaderStages::COMPUTE,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Storage { read_only: false },
                    has_dynamic_offset: false,
                    min_binding_size: None,
                },
                count: None,
            },
        ],
    });
    let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some("read samples"),
        bind_group_layouts: &[Some(&layout)],
        immediate_size: 0,
    });
    let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some("read samples"),
        layout: Some(&pipeline_layout),
        module: &module,
        entry_point: Some("main"),
        compilation_options: Default::default(),
        cache: None,
    });
    let (width, height) = (texture.width(), texture.height());
    let count = u64::from(width) * u64::from(height) * u64::from(samples);
    let buffer = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("read samples"),
        size: count * 16,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    let view = texture.create_view(&wgpu::TextureViewDescriptor {
        aspect: wgpu::TextureAspect::All,
        ..Default::default()
    });
    let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("read samples"),
        layout: &layout,
        entries: &[
            wgpu::BindGroupEntry {
                binding: 0,
                resource: wgpu::BindingResource::TextureView(&view),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: buffer.as_entire_binding(),
            },
        ],
    });
    let mut encoder = device.create_command_encoder(&Default::default());
    {
        let mut pass = encoder.begin_compute_pass(&Default::default());
        pass.set_pipeline(&pipeline);
        pass.set_bind_group(0, &bind_group, &[]);
        pass.dispatch_workgroups(width.div_ceil(8), height.div_ceil(8), 1);
    }
    gpu.queue.submit([encoder.finish()]);
    let bytes = read_buffer(device, &gpu.queue, &buffer)
        .unwrap_or_else(|e| panic!("cannot read the samples back: {e}"));
    let texels: Vec<[f32; 4]> = bytes
        .chunks_exact(16)
        .map(|t| {
            let f =
                |i: usize| f32::from_le_bytes([t[4 * i], t[4 * i + 1], t[4 * i + 2], t[4 * i + 3]]);
            [f(0), f(1), f(2), f(3)]
        })
        .collect();
    texels
        .chunks_exact(samples as usize)
        .map(<[_]>::to_vec)
        .collect()
}

impl Frame {
    /// Every sample of the exported float texture `name` (see [`read_samples`]).
    pub fn samples(&self, gpu: &Gpu, name: &str) -> Vec<Vec<[f32; 4]>> {
        read_samples(gpu, self.texture(name))
    }
}
