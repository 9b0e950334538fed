//! `visibility_compute`: the visibility pass rasterised in compute (Nanite's software
//! rasteriser in spirit: Karis et al., "Nanite", SIGGRAPH 2021): the host's opaque
//! meshes into a graph buffer of one 64-bit key per sample, depth over triangle ID,
//! kept by `atomicMax` (common/visibility_samples.rs; visibility_raster.wgsl says how
//! triangles are covered). No render targets and no ROPs: on a chip with few of them
//! (the H200), a multisampled raster pass pays per sample written whatever it holds,
//! and the hardware visibility pass at 4x took 3.6x its 1x time.
//!
//! ```ron
//! (name: "visibility", plugin: "visibility_compute",
//!  outputs: { "samples": "samples" })    // Buffer(per_sample: 8, samples: 4)
//! ```
//!
//! `light_tiled` with a `samples` input shades it as it shades a hardware visibility
//! buffer's `ids` and `depth`, with the same IDs (the triangle's position in the scene's
//! index buffer / 3, + 1) and the same sample positions. Depth is reversed-Z (1 near,
//! 0 far), the convention a float depth buffer gets. Needs 64-bit atomic min/max
//! (`int64_atomics`, a device condition: pipelines/visibility_compute_4x.ron falls back
//! to nothing, so a device without them gets an error naming the condition). Alpha MASK
//! draws are tested as the hardware pass tests them: their base colour's alpha times the
//! vertex colour's, at the pixel centre, against the cutoff (a textured base colour's
//! alpha is not read: such scenes are `untabled_textures`, which the pipelines keep from
//! this pass). Alpha BLEND draws are left out, as with a G-buffer: the transparent pass
//! draws them later, testing against the depth `keys_depth` makes from the keys.

use serde::Deserialize;

use graph_core::file::{Plugin, PluginError, Slots};
use graph_core::types::Features;
use graph_core::{Buffer, BufferHandle, BufferRole, PassBuilder, PassKind};

use crate::common::plugin::{Recording, Shared};
use crate::common::visibility_samples;
use crate::shaders;

pub struct VisibilityCompute(pub(crate) Shared);

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VisibilityComputeParams {}

/// What the shader needs of the device: 64-bit integers and their atomic min and max.
pub(crate) const NEEDS: Features =
    Features::SHADER_INT64.union(Features::SHADER_INT64_ATOMIC_MIN_MAX);

/// The pass as set up: what its `gpu` module records.
#[cfg_attr(not(feature = "gpu"), allow(dead_code))]
pub(crate) struct RasterDispatch {
    pub source: String,
    pub samples: BufferHandle,
}

impl Recording for RasterDispatch {
    #[cfg(feature = "gpu")]
    fn record(self, scenes: std::sync::Arc<crate::gpu_scene::SceneCache>) -> graph_core::Record {
        graph_core::Record::Compute(gpu::record(self, scenes))
    }
}

impl Plugin for VisibilityCompute {
    const NAME: &'static str = "visibility_compute";
    type Params = VisibilityComputeParams;

    fn kind(&self, _: &VisibilityComputeParams) -> PassKind {
        PassKind::Compute
    }

    fn setup(
        &self,
        _: VisibilityComputeParams,
        pass: &mut PassBuilder<'_>,
        slots: &mut Slots<'_>,
    ) -> Result<(), PluginError> {
        // Cleared before it is drawn into: nothing of an earlier version is read.
        let role = BufferRole::Storage {
            read: false,
            write: true,
        };
        let samples = slots.write::<Buffer>("samples", |t| pass.buffer(t.handle, role))?;
        let count = visibility_samples::sample_count(pass, slots, "samples", samples)?;
        let shader = shaders::VISIBILITY_RASTER.compose_for(count, "", NEEDS)?;
        let dispatch = RasterDispatch {
            source: shader.source().to_owned(),
            samples,
        };
        self.0.record(pass, dispatch);
        Ok(())
    }
}

#[cfg(feature = "gpu")]
mod gpu {
    //! Recording: the clear, raster and item dispatches of visibility_raster.wgsl, with
    //! the opaque draws' table and the work lists made once per scene upload.

    use std::sync::Arc;

    use graph_core::gpu::ComputeContext;
    use wgpu::util::DeviceExt;

    use super::RasterDispatch;
    use crate::common::gpu::pipeline::{module, pipeline_layout};
    use crate::common::gpu::{compute_pipeline, per_scene};
    use crate::common::visibility_samples::{fits_binding, KEY_BYTES};
    use crate::gpu_scene::{GpuScene, SceneCache};
    use crate::scene::DepthConvention;

    /// Triangles too large for one invocation the lists hold (80 bytes each), and their
    /// items (8 bytes each: up to 16 blocks of 8 x 8 pixels). Beyond them, triangles are
    /// covered by their own invocation: slower, never wrong.
    const LISTED: u64 = 1 << 17;
    const ITEMS: u64 = 1 << 20;
    /// visibility_raster.wgsl's workgroup of cs_clear and cs_raster, and the grid of
    /// cs_raster_items.
    const GROUP: u32 = 64;
    const ITEM_GROUPS: u32 = 1024;

    /// visibility_raster.wgsl's RasterDraw.
    #[repr(C)]
    #[derive(Copy, Clone, bytemuck::Pod, bytemuck::Zeroable)]
    struct RasterDraw {
        first_triangle: u32,
        triangles: u32,
        start: u32,
        mesh: u32,
        flags: u32,
    }

    /// visibility_raster.wgsl's RasterDraw flags.
    const CULL: u32 = 1;
    const MASKED: u32 = 2;

    struct State {
        layout: wgpu::BindGroupLayout,
        clear: wgpu::ComputePipeline,
        raster: wgpu::ComputePipeline,
        items: wgpu::ComputePipeline,
        draws: wgpu::Buffer,
        triangles: u32,
        counts: wgpu::Buffer,
        listed: wgpu::Buffer,
        item_list: wgpu::Buffer,
    }

    pub(super) fn record(
        dispatch: RasterDispatch,
        scenes: Arc<SceneCache>,
    ) -> Box<dyn FnMut(&mut ComputeContext<'_, '_>)> {
        let mut state = None;
        Box::new(move |ctx| {
            let resources = ctx.resources;
            let device = resources.device;
            let Some(scene) = scenes.for_frame(resources) else {
                return;
            };
            let state = per_scene(&mut state, &scene, || {
                build(device, &dispatch.source, &scene)
            });
            let geometry = match scene.geometry_group(device) {
                Ok(group) => group,
                Err(why) => return resources.fail(why),
            };
            let keys = resources.buffer(dispatch.samples);
            if let Err(why) = fits_binding(device, keys) {
                return resources.fail(why);
            }
            let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("visibility_compute"),
                layout: &state.layout,
                entries: &[
                    keys,
                    &state.draws,
                    &state.counts,
                    &state.listed,
                    &state.item_list,
                ]
                .into_iter()
                .zip(0..)
                .map(|(buffer, binding)| wgpu::BindGroupEntry {
                    binding,
                    resource: buffer.as_entire_binding(),
                })
                .collect::<Vec<_>>(),
            });
            let pass = &mut ctx.pass;
            pass.set_bind_group(0, scene.bind_group(DepthConvention::ReversedZ), &[]);
            pass.set_bind_group(1, &group, &[]);
            pass.set_bind_group(2, geometry, &[]);
            let (x, y) = grid(keys.size() / KEY_BYTES);
            pass.set_pipeline(&state.clear);
            pass.dispatch_workgroups(x, y, 1);
            if state.triangles > 0 {
                let (x, y) = grid(u64::from(state.triangles));
                pass.set_pipeline(&state.raster);
                pass.dispatch_workgroups(x, y, 1);
                pass.set_pipeline(&state.items);
                pass.dispatch_workgroups(ITEM_GROUPS, 1, 1);
            }
        })
    }

    /// Workgroups of GROUP invocations for `invocations`, as x by y within the 65,535 a
    /// dimension allows (the shader flattens them back).
    fn grid(invocations: u64) -> (u32, u32) {
        let groups = invocations.div_ceil(u64::from(GROUP)).max(1);
        let x = groups.min(65_535);
        (x as u32, groups.div_ceil(x) as u32)
    }

    fn build(device: &wgpu::Device, source: &str, scene: &GpuScene) -> State {
        let storage = |binding, read_only| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::COMPUTE,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Storage { read_only },
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            count: None,
        };
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("visibility_compute"),
            entries: &[
                storage(0, false),
                storage(1, true),
                storage(2, false),
                storage(3, false),
                storage(4, false),
            ],
        });
        let module = module(device, "visibility_compute", source);
        let pipeline_layout = pipeline_layout(
            device,
            &[
                Some(scene.layout()),
                Some(&layout),
                Some(scene.geometry_layout()),
            ],
        );
        let constants = [("ITEM_GROUPS", f64::from(ITEM_GROUPS))];
        let label = "visibility_compute";
        let pipeline = |entry: &str| {
            compute_pipeline(device, label, &pipeline_layout, &module, entry, &constants)
        };
        let (mut draws, triangles) = raster_draws(scene);
        if draws.is_empty() {
            // Nothing opaque: one zeroed entry keeps the group whole; the clear runs
            // alone and nothing reads it.
            draws.push(bytemuck::Zeroable::zeroed());
        }
        let scratch = |label, size| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size,
                usage: wgpu::BufferUsages::STORAGE,
                mapped_at_creation: false,
            })
        };
        State {
            clear: pipeline("cs_clear"),
            raster: pipeline("cs_raster"),
            items: pipeline("cs_raster_items"),
            layout,
            draws: device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("visibility_compute draws"),
                contents: bytemuck::cast_slice(&draws),
                usage: wgpu::BufferUsages::STORAGE,
            }),
            triangles,
            counts: scratch("visibility_compute counts", 8),
            listed: scratch("visibility_compute listed", LISTED * 80),
            item_list: scratch("visibility_compute items", ITEMS * 8),
        }
    }

    /// The opaque draws (alpha BLEND ones are the transparent pass's), each after the
    /// triangles of those before it, and their triangles in all.
    fn raster_draws(scene: &GpuScene) -> (Vec<RasterDraw>, u32) {
        let mut start = 0;
        let draws = scene
            .mesh_draws()
            .filter(|(_, state)| !state.blended)
            .map(|(draw, state)| {
                let triangles = (draw.indices.end - draw.indices.start) / 3;
                let entry = RasterDraw {
                    first_triangle: draw.indices.start / 3,
                    triangles,
                    start,
                    mesh: draw.instance,
                    flags: match state.double_sided {
                        true => 0,
                        false => CULL,
                    } | match state.masked {
                        true => MASKED,
                        false => 0,
                    },
                };
                start += triangles;
                entry
            })
            .collect();
        (draws, start)
    }
}
