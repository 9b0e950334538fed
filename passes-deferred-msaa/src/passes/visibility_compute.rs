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

    use super::RasterDispatch;
    use crate::common::gpu::pipeline::{module, pipeline_layout};
    use crate::common::gpu::raster_draws::{grid, RasterDraws};
    use crate::common::gpu::storage::{scratch, storage_group, storage_layout};
    use crate::common::gpu::{compute_pipeline, per_scene};
    use crate::common::visibility_samples::{fits_binding, KEY_BYTES};
    use crate::gpu_scene::{GpuScene, SceneCache};
    use crate::scene::DepthConvention;
    use graph_core::gpu::ComputeContext;

    /// Triangles too large for one invocation the lists hold (80 bytes each), and their
    /// items (8 bytes each: up to 16 blocks of 8 x 8 pixels). Beyond them, triangles are
    /// covered by their own invocation: slower, never wrong.
    const LISTED: u64 = 1 << 17;
    const ITEMS: u64 = 1 << 20;
    /// visibility_raster.wgsl's workgroup of cs_clear and cs_raster, and the grid of
    /// cs_raster_items.
    const GROUP: u32 = 64;
    const ITEM_GROUPS: u32 = 1024;

    struct State {
        layout: wgpu::BindGroupLayout,
        clear: wgpu::ComputePipeline,
        raster: wgpu::ComputePipeline,
        items: wgpu::ComputePipeline,
        draws: RasterDraws,
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
            let group = storage_group(
                device,
                "visibility_compute",
                &state.layout,
                &[
                    keys,
                    &state.draws.buffer,
                    &state.counts,
                    &state.listed,
                    &state.item_list,
                ],
            );
            let pass = &mut ctx.pass;
            pass.set_bind_group(0, scene.bind_group(DepthConvention::ReversedZ), &[]);
            pass.set_bind_group(1, &group, &[]);
            pass.set_bind_group(2, geometry, &[]);
            let (x, y) = grid(keys.size() / KEY_BYTES, GROUP);
            pass.set_pipeline(&state.clear);
            pass.dispatch_workgroups(x, y, 1);
            if state.draws.triangles > 0 {
                let (x, y) = grid(u64::from(state.draws.triangles), GROUP);
                pass.set_pipeline(&state.raster);
                pass.dispatch_workgroups(x, y, 1);
                pass.set_pipeline(&state.items);
                pass.dispatch_workgroups(ITEM_GROUPS, 1, 1);
            }
        })
    }

    fn build(device: &wgpu::Device, source: &str, scene: &GpuScene) -> State {
        let layout = storage_layout(
            device,
            "visibility_compute",
            &[false, true, false, false, false],
        );
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
        State {
            clear: pipeline("cs_clear"),
            raster: pipeline("cs_raster"),
            items: pipeline("cs_raster_items"),
            layout,
            draws: RasterDraws::new(device, scene),
            counts: scratch(device, "visibility_compute counts", 8),
            listed: scratch(device, "visibility_compute listed", LISTED * 80),
            item_list: scratch(device, "visibility_compute items", ITEMS * 8),
        }
    }
}
