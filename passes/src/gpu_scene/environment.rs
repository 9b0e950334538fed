//! Image-based lighting on the device: the prefiltered cube map and the split-sum lookup
//! table (scene/src/prefilter.rs) and their sampler, group 0 bindings 5 to 7 (lighting.wgsl).
//! The table's blue channel holds the sheen lobe's albedo (scene/src/sheen.rs), which
//! brdf.wgsl scales KHR_materials_sheen's base by under any light. A scene without an
//! environment binds one black texel for the cube map, and for the table too unless it
//! has a sheen: its shaders compile the environment out (the `ENVIRONMENT` gate), but the
//! layout is the same for every scene.

use wgpu::TextureViewDimension::{Cube, D2};

use super::textures::create;
use rgraph_scene::{
    prefiltered_cube, sheen_albedo_lut, split_sum_lut, Scene, CUBE_LEVELS, CUBE_SIZE, LUT_SIZE,
};

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
        let black = [0u8; 8];
        let cube = match scene.environment {
            Some(_) => create(
                device,
                queue,
                "environment",
                (CUBE_SIZE, CUBE_SIZE, CUBE_LEVELS),
                format,
                Cube,
                &halves(&mut prefiltered_cube().iter().flatten().copied()),
            ),
            None => create(
                device,
                queue,
                "no environment",
                (1, 1, 1),
                format,
                Cube,
                &black.repeat(6),
            ),
        };
        let sheen = scene.materials.iter().any(|m| m.has_sheen());
        let lut = match scene.environment.is_some() || sheen {
            true => {
                let texels = split_sum_lut().iter().zip(sheen_albedo_lut());
                let lut = halves(&mut texels.flat_map(|(&[a, b], &e)| [a, b, e, 1.0]));
                create(
                    device,
                    queue,
                    "split-sum LUT",
                    (LUT_SIZE, LUT_SIZE, 1),
                    format,
                    D2,
                    &lut,
                )
            }
            false => create(
                device,
                queue,
                "no split-sum LUT",
                (1, 1, 1),
                format,
                D2,
                &black,
            ),
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
