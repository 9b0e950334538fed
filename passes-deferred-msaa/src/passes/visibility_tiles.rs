//! `visibility_tiles`: the visibility pass rasterised in compute tile by tile, into the
//! same graph buffer of keys as `visibility_compute` (common/visibility_samples.rs), with
//! neither atomics into memory nor 64-bit integers. The opaque triangles are binned to
//! tiles first (common/gpu/tile_bins.rs, tile_bins.wgsl); then a workgroup per tile
//! covers its triangles in registers, an invocation per pixel (tile_raster.wgsl), and
//! stores each pixel's keys once (visibility_tiles_raster.wgsl). The same coverage rules
//! and keys as visibility_compute's: the same buffer, bit for bit.
//!
//! ```ron
//! (name: "visibility", plugin: "visibility_tiles",
//!  params: (tile: 16),                   // pixels per tile side, 4 to 16
//!  outputs: { "samples": "samples" })    // Buffer(per_sample: 8, samples: 4)
//! ```
//!
//! At 4x, visibility_compute's atomicMax per covered sample lands anywhere in a buffer
//! five times the H200's L2; here each tile's keys are written once, in rows. Alpha MASK
//! and BLEND draws as visibility_compute takes them.

use serde::Deserialize;

use graph_core::file::{Plugin, PluginError, Slots};
use graph_core::shader::Stage;
use graph_core::{Buffer, BufferHandle, BufferRole, PassBuilder, PassKind};

use crate::common::plugin::{Recording, Shared};
use crate::common::visibility_samples;
use crate::shaders;

pub struct VisibilityTiles(pub(crate) Shared);

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VisibilityTilesParams {
    #[serde(default = "tile")]
    pub tile: u32,
}

fn tile() -> u32 {
    16
}

/// Tile sides allowed: a workgroup of 16 x 16 invocations is WebGPU's largest.
const TILES: std::ops::RangeInclusive<u32> = 4..=16;

/// The pass as set up: what its `gpu` module records.
#[cfg_attr(not(feature = "gpu"), allow(dead_code))]
pub(crate) struct TilesDispatch {
    pub raster: String,
    pub bins: String,
    pub tile: u32,
    pub samples: BufferHandle,
}

impl Recording for TilesDispatch {
    #[cfg(feature = "gpu")]
    fn record(self, scenes: std::sync::Arc<crate::gpu_scene::SceneCache>) -> graph_core::Record {
        graph_core::Record::Compute(gpu::record(self, scenes))
    }
}

impl Plugin for VisibilityTiles {
    const NAME: &'static str = "visibility_tiles";
    type Params = VisibilityTilesParams;

    fn kind(&self, _: &VisibilityTilesParams) -> PassKind {
        PassKind::Compute
    }

    fn setup(
        &self,
        params: VisibilityTilesParams,
        pass: &mut PassBuilder<'_>,
        slots: &mut Slots<'_>,
    ) -> Result<(), PluginError> {
        if !TILES.contains(&params.tile) {
            return Err(PluginError::Invalid(format!(
                "tile must be {} to {} pixels, got {}",
                TILES.start(),
                TILES.end(),
                params.tile
            )));
        }
        // Every key is stored each frame: nothing of an earlier version is read.
        let role = BufferRole::Storage {
            read: false,
            write: true,
        };
        let samples = slots.write::<Buffer>("samples", |t| pass.buffer(t.handle, role))?;
        let count = visibility_samples::sample_count(pass, slots, "samples", samples)?;
        let generated = format!(
            "// Generated: the tile's side in pixels, then the sample lanes.\n\
             const TILE: u32 = {}u;\n{}",
            params.tile,
            shaders::sample_lanes(count)
        );
        let raster = shaders::TILE_RASTER.compose_with(count, &generated)?;
        let Some(entry) = raster.entry("cs_raster_tiles", Stage::Compute) else {
            return Err(PluginError::Invalid(
                "visibility_tiles_raster.wgsl has no entry point cs_raster_tiles".into(),
            ));
        };
        pass.workgroup(entry.workgroup());
        let dispatch = TilesDispatch {
            raster: raster.source().to_owned(),
            bins: shaders::TILE_BINS.compose(count)?.source().to_owned(),
            tile: params.tile,
            samples,
        };
        self.0.record(pass, dispatch);
        Ok(())
    }
}

#[cfg(feature = "gpu")]
mod gpu {
    //! Recording: the bins' dispatches, then one workgroup per tile, with the bins and
    //! pipelines made once per scene upload.

    use std::sync::Arc;

    use graph_core::gpu::ComputeContext;

    use super::TilesDispatch;
    use crate::common::gpu::pipeline::{module, pipeline_layout};
    use crate::common::gpu::storage::{storage_group_at, storage_layout_at};
    use crate::common::gpu::tile_bins::TileBins;
    use crate::common::gpu::{compute_pipeline, per_scene};
    use crate::common::visibility_samples::fits_binding;
    use crate::gpu_scene::{GpuScene, SceneCache};
    use crate::scene::DepthConvention;

    struct State {
        bins: TileBins,
        layout: wgpu::BindGroupLayout,
        raster: wgpu::ComputePipeline,
    }

    pub(super) fn record(
        dispatch: TilesDispatch,
        scenes: Arc<SceneCache>,
    ) -> Box<dyn FnMut(&mut ComputeContext<'_, '_>)> {
        let mut state = None;
        Box::new(move |ctx| {
            let resources = ctx.resources;
            let device = resources.device;
            let Some(scene) = scenes.for_frame(resources) else {
                return;
            };
            let size = resources.output_size();
            let state = per_scene(&mut state, &scene, || {
                build(device, &dispatch, &scene, size)
            });
            let state = match state {
                Ok(state) => state,
                Err(why) => return resources.fail(why.clone()),
            };
            let geometry = match scene.geometry_group(device) {
                Ok(group) => group,
                Err(why) => return resources.fail(why),
            };
            let keys = resources.buffer(dispatch.samples);
            if let Err(why) = fits_binding(device, keys) {
                return resources.fail(why);
            }
            let mut buffers = vec![(0, keys)];
            buffers.extend(state.bins.raster_buffers());
            let group = storage_group_at(device, "visibility_tiles", &state.layout, &buffers);
            state.bins.record(&mut ctx.pass, &scene, geometry);
            let pass = &mut ctx.pass;
            pass.set_bind_group(0, scene.bind_group(DepthConvention::ReversedZ), &[]);
            pass.set_bind_group(1, &group, &[]);
            pass.set_bind_group(2, geometry, &[]);
            pass.set_pipeline(&state.raster);
            pass.dispatch_workgroups(
                size.0.div_ceil(dispatch.tile),
                size.1.div_ceil(dispatch.tile),
                1,
            );
        })
    }

    fn build(
        device: &wgpu::Device,
        dispatch: &TilesDispatch,
        scene: &GpuScene,
        size: (u32, u32),
    ) -> Result<State, String> {
        let bins = TileBins::new(device, &dispatch.bins, scene, dispatch.tile, size)?;
        let mut bindings = vec![(0, false)];
        bindings.extend(
            bins.raster_buffers()
                .iter()
                .map(|&(binding, _)| (binding, true)),
        );
        let layout = storage_layout_at(device, "visibility_tiles", &bindings);
        let module = module(device, "visibility_tiles", &dispatch.raster);
        let pipeline_layout = pipeline_layout(
            device,
            &[
                Some(scene.layout()),
                Some(&layout),
                Some(scene.geometry_layout()),
            ],
        );
        let raster = compute_pipeline(
            device,
            "visibility_tiles",
            &pipeline_layout,
            &module,
            "cs_raster_tiles",
            &[],
        );
        Ok(State {
            bins,
            layout,
            raster,
        })
    }
}
