//! Image-based lighting on the device: the prefiltered cube map and the split-sum lookup
//! table (scene/src/prefilter.rs) and their sampler, group 0 bindings 5 to 7 (lighting.wgsl).
//! A scene without an environment binds one black texel of each: its shaders compile the
//! environment out (the `ENVIRONMENT` gate), but the layout is the same for every scene.

use wgpu::TextureViewDimension::{Cube, D2};

use super::textures::create;
use rgraph_scene::{prefiltered_cube, split_sum_lut, Scene, CUBE_LEVELS, CUBE_SIZE, LUT_SIZE};

pub(super) struct EnvironmentMaps {
    pub cube: wgpu::TextureView,
    pub lut: wgpu::TextureView,
    pub sampler: wgpu::Sampler,
}

impl EnvironmentMaps {
    pub fn new(device: &wgpu::Device, queue: &wgpu::Queue, scene: &Scene) -> EnvironmentMaps {
        let format = wgpu::TextureFormat::Rgba16Float;
        let halves = |values: &mut dyn Iterator<Item = f32>| -> Vec<u8> {
            values
                .flat_map(|v| half::f16::from_f32(v).to_le_bytes())
                .collect()
        };
        let (cube, lut) = match scene.environment {
            Some(_) => {
                let cube = halves(&mut prefiltered_cube().iter().flatten().copied());
                let lut = halves(&mut split_sum_lut().iter().flat_map(|&[a, b]| [a, b, 0.0, 1.0]));
                let cube_size = (CUBE_SIZE, CUBE_SIZE, CUBE_LEVELS);
                (
                    create(device, queue, "environment", cube_size, format, Cube, &cube),
                    create(
                        device,
                        queue,
                        "split-sum LUT",
                        (LUT_SIZE, LUT_SIZE, 1),
                        format,
                        D2,
                        &lut,
                    ),
                )
            }
            None => {
                let black = [0u8; 8];
                (
                    create(
                        device,
                        queue,
                        "no environment",
                        (1, 1, 1),
                        format,
                        Cube,
                        &black.repeat(6),
                    ),
                    create(
                        device,
                        queue,
                        "no split-sum LUT",
                        (1, 1, 1),
                        format,
                        D2,
                        &black,
                    ),
                )
            }
        };
        let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("environment"),
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            mipmap_filter: wgpu::MipmapFilterMode::Linear,
            ..Default::default()
        });
        EnvironmentMaps { cube, lut, sampler }
    }
}
