//! `shadow_raster`: the shadow maps rasterised in compute into a buffer of one key per
//! atlas texel, which `shadow_resolve` writes into the atlas with what the hardware drew
//! of alpha MASK meshes (`shadow_maps`).
//!
//! ```ron
//! (name: "shadow raster", plugin: "shadow_raster",
//!  when: "shadows & !cpu_device",
//!  params: (slope_bias: 2.0,     // the default, as shadow_maps': the same depth bias
//!           small_texels: 16,    // the default: the most texels a small cluster spans
//!           cache: true),        // the default with `previous`: nothing drawn while nothing moved
//!  inputs: { "previous": "shadow_atlas_prev" },  // History(of: "shadow_atlas"), with cache
//!  outputs: { "keys": "shadow_keys" })   // Buffer(size: 4 N^2) for an N-texel atlas
//! ```
//!
//! With `cache`, a frame whose shadow work has the stamp of the last one drawn, and whose
//! `previous` atlas was not reset, draws nothing: `shadow_resolve` copies that atlas
//! (common/shadow_cache.rs says when, and why the raster reads the history).
//!
//! Each frame the pass clears the keys, asks the scene for the frame's shadow work
//! (gpu_scene/shadow_work.rs: each view's runs of each opaque mesh, culled by the view
//! and split into small and large clusters), uploads its runs where the work is not the
//! last uploaded (20 bytes a run, whatever its length: each dispatch's workgroups take
//! chunks of 64 triangles, and find their run by a binary search of the runs' first
//! chunks) and covers their triangles: corners projected into the view's tile, the
//! texels of each row's span (the columns the triangle's edges leave of its bounds)
//! tested by edge functions, the depth interpolated, the hardware's slope-scaled bias
//! added, and the nearest kept by `atomicMax` of the depth's bits inverted. A small
//! cluster (wholly between the view's depth planes, spanning at most `small_texels`
//! texels) takes an invocation a triangle; a large one a workgroup of 256 invocations a
//! chunk, each triangle clipped to the near plane, and the chunk's rows' texels shared
//! out evenly (a prefix sum over each 256 rows' spans); and a triangle whose bounds hold
//! more than 4096 texels (a ground plane across a view) is handed on in chunks of 4096 to
//! a third dispatch, whose workgroups spread over the GPU: on an H100 a workgroup
//! covering each view's ground alone took the 4096-texel atlas of `builtin:dense` with 9
//! shadowed lights 5.4 ms against the hardware's 3.0. Alpha
//! MASK meshes are left to the hardware, which tests their textures. On an H100 the
//! hardware raster writes 7 to 9 Gtexel/s of depth (its graphics TPCs are few): a
//! 4096-texel atlas took it 2 to 3 ms, a 10M-triangle heightfield's 22 views 122 ms
//! (docs/design/shadows.md); this is the compute raster issue 39 asks for.

use serde::Deserialize;

use rgraph_core::file::{Plugin, PluginError, Slots};
use rgraph_core::{Buffer, BufferHandle, BufferRole, PassBuilder, PassKind, TextureHandle};

use crate::common::plugin::Shared;
use crate::common::shadow_cache;
use crate::common::shadow_depth::{self, check_slope_bias};
use crate::common::switch::Switch;
use crate::shaders;

pub struct ShadowRaster(pub(crate) Shared);

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ShadowRasterParams {
    /// The slope-scaled depth bias, as `shadow_maps`' (the hardware's rule: the bias is
    /// this times the larger of the depth's changes per texel across and down).
    #[serde(default = "shadow_depth::slope_bias")]
    pub slope_bias: f32,
    /// The most texels a cluster's box may span in a view to be small, an invocation a
    /// triangle (each loops over its triangle's texels, at most this squared).
    #[serde(default = "small_texels")]
    pub small_texels: u32,
    /// Whether the last frame's atlas is kept while nothing it shows moved: by default
    /// where the file gives a `previous` input.
    #[serde(default)]
    pub cache: Option<Switch>,
}

fn small_texels() -> u32 {
    16
}

/// The pass as set up: what its `gpu` module records.
#[cfg_attr(not(feature = "gpu"), allow(dead_code))]
pub(crate) struct ShadowRasterDispatch {
    pub source: String,
    pub keys: BufferHandle,
    pub slope_bias: f32,
    pub small_texels: u32,
    /// The last frame's atlas, whose reset the pass asks about, where it is kept.
    pub previous: Option<TextureHandle>,
}

impl Plugin for ShadowRaster {
    const NAME: &'static str = "shadow_raster";
    type Params = ShadowRasterParams;

    fn kind(&self, _: &ShadowRasterParams) -> PassKind {
        PassKind::Compute
    }

    fn setup(
        &self,
        params: ShadowRasterParams,
        pass: &mut PassBuilder<'_>,
        slots: &mut Slots<'_>,
    ) -> Result<(), PluginError> {
        check_slope_bias(params.slope_bias)?;
        if !(1..=64).contains(&params.small_texels) {
            return Err(PluginError::Invalid(format!(
                "small_texels must be 1 to 64, got {}",
                params.small_texels
            )));
        }
        // Cleared and written each frame (atomics read what this frame wrote): nothing
        // of an earlier version is read.
        let role = BufferRole::Storage {
            read: false,
            write: true,
        };
        let keys = slots.write::<Buffer>("keys", |t| pass.buffer(t.handle, role))?;
        let previous = shadow_cache::previous(params.cache, pass, slots)?;
        let dispatch = ShadowRasterDispatch {
            source: shaders::SHADOW_COMPUTE.compose(1)?.source().to_owned(),
            keys,
            slope_bias: params.slope_bias,
            small_texels: params.small_texels,
            previous,
        };
        self.0.record(pass, dispatch);
        Ok(())
    }
}

#[cfg(feature = "gpu")]
mod gpu {
    //! Recording: the keys cleared, the frame's runs uploaded into a buffer the pass
    //! keeps (grown as a frame needs), one workgroup a chunk of a run.

    use std::sync::Arc;

    use super::ShadowRasterDispatch;
    use crate::common::gpu::pipeline::{module, pipeline_layout};
    use crate::common::gpu::shadow_cache::Kept;
    use crate::common::gpu::storage::{storage_group, storage_layout};
    use crate::common::gpu::{
        compute_pipeline, workgroup_grid, Compute, Frame, Recorded, Recorder,
    };
    use crate::common::shadow_depth::atlas_of_keys;
    use crate::gpu_scene::{GpuScene, RasterRun, ShadowOptions, ShadowWork};
    use rgraph_scene::DepthConvention;

    pub(crate) struct State {
        layout: wgpu::BindGroupLayout,
        clear: wgpu::ComputePipeline,
        raster: wgpu::ComputePipeline,
        large: wgpu::ComputePipeline,
        huge: wgpu::ComputePipeline,
        /// The runs and the parameters (`RasterParams`), and the work they were written
        /// from with those parameters.
        runs: Option<wgpu::Buffer>,
        params: wgpu::Buffer,
        uploaded: Option<(Arc<ShadowWork>, Params)>,
        /// The huge triangles handed on and their chunks, for an atlas of this side.
        handed_on: Option<(u32, [wgpu::Buffer; 2])>,
        kept: Kept,
    }

    /// shadow_compute.wgsl's `RasterParams`: the atlas's side, the slope bias's bits, the
    /// small and large runs, the small and large chunks.
    type Params = [u32; 6];

    /// Writes `work`'s runs into `state.runs` (grown as needed) and its parameters for an
    /// atlas of `atlas` texels and `slope_bias`; the parameters.
    fn upload(
        state: &mut State,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        work: &ShadowWork,
        atlas: u32,
        slope_bias: f32,
    ) -> Result<Params, String> {
        let runs = work.raster_runs();
        let count = |n: usize| u32::try_from(n).map_err(|_| "too many shadow runs".to_owned());
        let (small, large) = (count(runs.small)?, count(runs.runs.len() - runs.small)?);
        let [small_chunks, large_chunks] = runs.chunks;
        // At least one run's room: wgpu refuses zero-sized bindings.
        let run = std::mem::size_of::<RasterRun>();
        let bytes = (runs.runs.len().max(1) * run) as u64;
        if state.runs.as_ref().is_some_and(|b| b.size() < bytes) {
            state.runs = None;
        }
        let buffer = state.runs.get_or_insert_with(|| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("shadow_raster runs"),
                size: bytes.next_power_of_two(),
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            })
        });
        queue.write_buffer(buffer, 0, bytemuck::cast_slice(&runs.runs));
        let params = [
            atlas,
            slope_bias.to_bits(),
            small,
            large,
            small_chunks,
            large_chunks,
        ];
        queue.write_buffer(&state.params, 0, bytemuck::cast_slice(&params));
        Ok(params)
    }

    /// Texels of a huge triangle's chunk (shadow_compute.wgsl's `HUGE_CHUNK`).
    const HUGE_CHUNK: u64 = 4096;
    /// Bytes of shadow_compute.wgsl's `Flat` in storage, and of `HugeFlats`' counts.
    const FLAT: u64 = 80;
    const COUNTS: u64 = 16;
    /// Workgroups of the huge triangles' dispatch: enough to fill a large GPU.
    const HUGE_GROUPS: u32 = 2048;

    /// `HugeFlats` and the chunks for an atlas of `side` texels: room for four chunks'
    /// worth of every texel of the atlas, and for a triangle per two chunks (a huge
    /// triangle has at least two). A frame needing more covers the rest slowly, in the
    /// large clusters' workgroups, never wrongly.
    fn handed_on(device: &wgpu::Device, side: u32) -> [wgpu::Buffer; 2] {
        let chunks = (4 * u64::from(side).pow(2) / HUGE_CHUNK).max(4096);
        let buffer = |label, size| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size,
                usage: wgpu::BufferUsages::STORAGE,
                mapped_at_creation: false,
            })
        };
        [
            buffer("shadow_raster huge triangles", COUNTS + FLAT * chunks / 2),
            buffer("shadow_raster huge chunks", 8 * chunks),
        ]
    }

    impl Recorder for ShadowRasterDispatch {
        type Stage = Compute;
        type Scene = Arc<GpuScene>;
        type State = State;

        fn build(&self, frame: &Frame<'_, '_, Self>) -> Result<State, String> {
            let (device, scene) = (frame.device, &frame.scene);
            let layout =
                storage_layout(device, "shadow_raster", &[false, true, true, false, false]);
            let module = module(device, "shadow_raster", &self.source);
            let pipeline_layout = pipeline_layout(
                device,
                &[
                    Some(scene.layout()),
                    Some(&layout),
                    Some(scene.geometry_layout()),
                ],
            );
            let pipeline = |entry| {
                compute_pipeline(
                    device,
                    "shadow_raster",
                    &pipeline_layout,
                    &module,
                    entry,
                    &[],
                )
            };
            Ok(State {
                clear: pipeline("cs_clear"),
                raster: pipeline("cs_shadow_raster"),
                large: pipeline("cs_shadow_raster_large"),
                huge: pipeline("cs_shadow_raster_huge"),
                layout,
                runs: None,
                uploaded: None,
                handed_on: None,
                kept: Kept::default(),
                params: device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("shadow_raster params"),
                    size: std::mem::size_of::<Params>() as u64,
                    usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                }),
            })
        }

        fn record(&self, state: &mut State, frame: &mut Frame<'_, '_, Self>) -> Recorded {
            let pass = &mut *frame.pass;
            let (resources, device, scene) = (frame.resources, frame.device, &frame.scene);
            let keys = resources.buffer(self.keys);
            let atlas = atlas_of_keys(keys.size()).ok_or_else(|| {
                format!(
                    "the keys buffer holds {} bytes, not 4 a texel of a square atlas",
                    keys.size()
                )
            })?;
            let options = ShadowOptions {
                culled: true,
                small_texels: Some(f64::from(self.small_texels)),
            };
            let work = scene.shadow_work(resources.queue, resources.output_size(), atlas, options);
            if let Some(previous) = self.previous {
                // The keys are left as they are: shadow_resolve copies the kept atlas.
                if state.kept.keeps(&work, resources.history_reset(previous)) {
                    return Ok(());
                }
            }
            // The buffers hold the last work uploaded: the same work (a frame whose
            // shadow inputs did not change, GpuScene::shadow_work) is not uploaded again.
            let params = match &state.uploaded {
                Some((uploaded, params)) if Arc::ptr_eq(uploaded, &work) => *params,
                _ => {
                    let params = upload(
                        state,
                        device,
                        resources.queue,
                        &work,
                        atlas,
                        self.slope_bias,
                    )?;
                    state.uploaded = Some((work.clone(), params));
                    params
                }
            };
            let [.., small, large] = params;
            let run_buffer = state.runs.as_ref().ok_or("no shadow runs")?;
            if state
                .handed_on
                .as_ref()
                .is_some_and(|(side, _)| *side != atlas)
            {
                state.handed_on = None;
            }
            let (_, [flats, chunks]) = state
                .handed_on
                .get_or_insert_with(|| (atlas, handed_on(device, atlas)));
            for buffer in [run_buffer, &state.params, flats, chunks] {
                resources.hold(buffer);
            }
            let group = storage_group(
                device,
                "shadow_raster",
                &state.layout,
                &[keys, run_buffer, &state.params, flats, chunks],
            );
            pass.set_bind_group(0, scene.bind_group(DepthConvention::Standard), &[]);
            pass.set_bind_group(1, &group, &[]);
            pass.set_bind_group(2, scene.geometry_group(device)?, &[]);
            pass.set_pipeline(&state.clear);
            // 256 keys a workgroup (shadow_compute.wgsl's cs_clear).
            let (x, y) = workgroup_grid(keys.size() / 4, 256);
            pass.dispatch_workgroups(x, y, 1);
            // A workgroup a chunk.
            for (pipeline, chunks) in [(&state.raster, small), (&state.large, large)] {
                if chunks > 0 {
                    pass.set_pipeline(pipeline);
                    let (x, y) = workgroup_grid(u64::from(chunks), 1);
                    pass.dispatch_workgroups(x, y, 1);
                }
            }
            // The large chunks' huge triangles: as many chunks as the large dispatch
            // handed on, which only the GPU knows, so a fixed grid that loops.
            if large > 0 {
                pass.set_pipeline(&state.huge);
                pass.dispatch_workgroups(HUGE_GROUPS, 1, 1);
            }
            Ok(())
        }
    }
}
