//! `depth_pyramid`: a compute rasteriser's keys as a depth pyramid, for occlusion culling
//! (common/occlusion.rs, cluster_occlusion.wgsl): each texel of each level holds the
//! farthest depth (reversed-Z: the least) of every sample of every pixel it covers, 0
//! where nothing was drawn.
//!
//! ```ron
//! (name: "depth pyramid", plugin: "depth_pyramid",
//!  params: (occlusion: true),                // false (or 0): records nothing
//!  inputs: { "samples": "keys" },            // Buffer(per_sample: 8, samples: N), every
//!                                            // sample's key stored
//!  outputs: { "pyramid": "depth_pyramid" })  // r32float, 1 sample, any size and mips
//! ```
//!
//! Level 0 from the keys, a texel per invocation over the pixels it covers (of a W x H
//! output and an N x M level, from floor(i W / N) to ceil((i + 1) W / N) - 1 across, so
//! any two sizes fit); then each level from the one before, a dispatch each, as 2 x 2
//! texels (depth_pyramid.wgsl). The shipped files make it 512 x 512 with 10 levels, a
//! size that holds every output: a level's size does not follow the output's, and a
//! file's mip count is a number. Every sample is read: a sloped triangle's samples lie at
//! different depths, and occlusion culling's test must hold for each (the keys of samples
//! other than 0 must be stored everywhere: `visibility_compute` does where it culls by
//! occlusion). With `occlusion: false` it records nothing, and the pyramid is whatever the
//! texture held: occlusion culling, off too, reads none of it.

use serde::Deserialize;

use rgraph_core::file::{Plugin, PluginError, Slots};
use rgraph_core::{BufferHandle, PassBuilder, PassKind, TextureHandle};

use crate::common::plugin::Shared;
use crate::common::switch::Switch;
use crate::common::textures::{self, Want};
use crate::common::visibility_samples;
use crate::shaders;

pub struct DepthPyramid(pub(crate) Shared);

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DepthPyramidParams {
    /// Whether the pyramid is built: yes unless occlusion culling is off.
    #[serde(default = "on")]
    pub occlusion: Switch,
}

fn on() -> Switch {
    Switch::On
}

/// The pass as set up: what its `gpu` module records.
#[cfg_attr(not(feature = "gpu"), allow(dead_code))]
struct PyramidDispatch {
    source: String,
    keys: BufferHandle,
    pyramid: TextureHandle,
}

impl Plugin for DepthPyramid {
    const NAME: &'static str = "depth_pyramid";
    type Params = DepthPyramidParams;

    fn kind(&self, _: &DepthPyramidParams) -> PassKind {
        PassKind::Compute
    }

    fn setup(
        &self,
        params: DepthPyramidParams,
        pass: &mut PassBuilder<'_>,
        slots: &mut Slots<'_>,
    ) -> Result<(), PluginError> {
        let (keys, samples) = visibility_samples::read(pass, slots, "samples")?;
        let want = Want::new("the depth pyramid", textures::VIEW_DEPTH).samples(1);
        let (pyramid, _) = textures::output(slots, pass, "pyramid", want, |pass, h, _| {
            pass.storage_write(h)
        })?;
        let source = shaders::DEPTH_PYRAMID.compose(samples)?;
        for entry in ["cs_pyramid_keys", "cs_pyramid_level"] {
            let Some(entry) = source.entry(entry, rgraph_core::shader::Stage::Compute) else {
                return Err(PluginError::Invalid(format!(
                    "depth_pyramid.wgsl has no entry point {entry}"
                )));
            };
            pass.workgroup(entry.workgroup());
        }
        if params.occlusion == Switch::On {
            let dispatch = PyramidDispatch {
                source: source.source().to_owned(),
                keys,
                pyramid,
            };
            self.0.record(pass, dispatch);
        }
        Ok(())
    }
}

#[cfg(feature = "gpu")]
mod gpu {
    //! Recording: level 0 from the keys, then a dispatch per level, each binding the
    //! level below as read-only storage and its own as write-only (views of one level
    //! each, made every frame: a history's texture changes from frame to frame).

    use std::sync::Arc;

    use super::PyramidDispatch;
    use crate::common::gpu::pipeline::{module, pipeline_layout};
    use crate::common::gpu::{compute_pipeline, Compute, Frame, Recorded, Recorder};
    use crate::common::visibility_samples::{fits_binding, KEYS_BINDING};
    use crate::gpu_scene::GpuScene;
    use rgraph_scene::DepthConvention;

    pub(crate) struct State {
        keys_layout: wgpu::BindGroupLayout,
        level_layout: wgpu::BindGroupLayout,
        from_keys: wgpu::ComputePipeline,
        from_level: wgpu::ComputePipeline,
    }

    /// depth_pyramid.wgsl's workgroup side.
    const GROUP: u32 = 8;

    fn storage_texture(
        binding: u32,
        access: wgpu::StorageTextureAccess,
    ) -> wgpu::BindGroupLayoutEntry {
        wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::COMPUTE,
            ty: wgpu::BindingType::StorageTexture {
                access,
                format: wgpu::TextureFormat::R32Float,
                view_dimension: wgpu::TextureViewDimension::D2,
            },
            count: None,
        }
    }

    impl Recorder for PyramidDispatch {
        type Stage = Compute;
        // The camera's viewport gives the keys' row length.
        type Scene = Arc<GpuScene>;
        type State = State;

        fn build(&self, frame: &Frame<'_, '_, Self>) -> Result<State, String> {
            let (device, scene) = (frame.device, &frame.scene);
            let layout =
                |label, entries: &[_]| crate::kept::bind_group_layout(device, label, entries);
            let keys_entry = wgpu::BindGroupLayoutEntry {
                binding: KEYS_BINDING,
                visibility: wgpu::ShaderStages::COMPUTE,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Storage { read_only: true },
                    has_dynamic_offset: false,
                    min_binding_size: None,
                },
                count: None,
            };
            let write = storage_texture(0, wgpu::StorageTextureAccess::WriteOnly);
            let read = storage_texture(1, wgpu::StorageTextureAccess::ReadOnly);
            let keys_layout = layout("depth pyramid: level 0", &[write, keys_entry]);
            let level_layout = layout("depth pyramid: levels", &[write, read]);
            let module = module(device, "depth pyramid", &self.source);
            let pipeline = |layout: &wgpu::BindGroupLayout, entry| {
                let groups = pipeline_layout(device, &[Some(scene.layout()), Some(layout)]);
                compute_pipeline(device, "depth pyramid", &groups, &module, entry, &[])
            };
            Ok(State {
                from_keys: pipeline(&keys_layout, "cs_pyramid_keys"),
                from_level: pipeline(&level_layout, "cs_pyramid_level"),
                keys_layout,
                level_layout,
            })
        }

        fn record(&self, state: &mut State, frame: &mut Frame<'_, '_, Self>) -> Recorded {
            let pass = &mut *frame.pass;
            let (resources, device) = (frame.resources, frame.device);
            let keys = resources.buffer(self.keys);
            fits_binding(device, keys)?;
            let texture = resources.texture(self.pyramid);
            let level = |k: u32| {
                texture.create_view(&wgpu::TextureViewDescriptor {
                    label: Some("depth pyramid level"),
                    base_mip_level: k,
                    mip_level_count: Some(1),
                    ..Default::default()
                })
            };
            let group = |layout, entries: &[wgpu::BindGroupEntry<'_>]| {
                device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some("depth pyramid"),
                    layout,
                    entries,
                })
            };
            let dispatch = |pass: &mut wgpu::ComputePass<'_>, k: u32| {
                let width = (texture.width() >> k).max(1);
                let height = (texture.height() >> k).max(1);
                pass.dispatch_workgroups(width.div_ceil(GROUP), height.div_ceil(GROUP), 1);
            };
            let camera = frame.scene.bind_group(DepthConvention::ReversedZ);
            pass.set_bind_group(0, camera, &[]);
            let mut below = level(0);
            let first = group(
                &state.keys_layout,
                &[
                    wgpu::BindGroupEntry {
                        binding: 0,
                        resource: wgpu::BindingResource::TextureView(&below),
                    },
                    wgpu::BindGroupEntry {
                        binding: KEYS_BINDING,
                        resource: keys.as_entire_binding(),
                    },
                ],
            );
            pass.set_pipeline(&state.from_keys);
            pass.set_bind_group(1, &first, &[]);
            dispatch(pass, 0);
            pass.set_pipeline(&state.from_level);
            for k in 1..texture.mip_level_count() {
                let this = level(k);
                let levels = group(
                    &state.level_layout,
                    &[
                        wgpu::BindGroupEntry {
                            binding: 0,
                            resource: wgpu::BindingResource::TextureView(&this),
                        },
                        wgpu::BindGroupEntry {
                            binding: 1,
                            resource: wgpu::BindingResource::TextureView(&below),
                        },
                    ],
                );
                pass.set_bind_group(1, &levels, &[]);
                dispatch(pass, k);
                below = this;
            }
            Ok(())
        }
    }
}
