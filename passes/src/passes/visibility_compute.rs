//! `visibility_compute`: the visibility pass rasterised in compute, tile by tile (the
//! design of Laine and Karras, "High-Performance Software Rasterization on GPUs", HPG
//! 2011: bin, then rasterise each tile on chip), into a graph buffer of one key per
//! sample: depth over triangle ID (common/visibility_samples.rs). No render targets and
//! no ROPs: on a chip with few of them (the H200), a multisampled raster pass pays per
//! sample written whatever it holds, and the hardware visibility pass at 4x took 3.6x its
//! 1x time. No atomics into memory and no 64-bit integers either: the opaque triangles
//! are binned to tiles first (common/gpu/tile_bins.rs, bin_triangles.wgsl); then a workgroup
//! per tile covers its triangles in registers, an invocation per pixel and a warp per
//! block of 4 x 8 pixels, which skips the triangles whose area misses its block
//! (tile_raster.wgsl), and stores each pixel's keys once, a plane per sample, with a
//! flag where they show more than one triangle (raster_tiles.wgsl, key_layout.wgsl):
//! the shading pass then reads a quarter of a 4x buffer away from edges. An atomicMax
//! per covered sample into the buffer, the design before, lands anywhere in a buffer
//! five times the H200's L2 at 4x and 3840x2160
//! (docs/design/compute-raster.md, run visibility-4x-attribution).
//!
//! ```ron
//! (name: "visibility", plugin: "visibility_compute",
//!  params: (
//!      tile: 16,                    // pixels per tile side, 4 to 16 (the default)
//!      other_samples: everywhere,   // or at_edges: below
//!      clusters: culled,            // or whole, or off: below
//!      occlusion: true,             // or false, with the slots below
//!      micro: true,                 // or false (the default): below
//!      micro_pixels: 4,             // 1 to 16 (the default 4): below
//!      binned_triangles: 100000,    // at least 1 (the default from the output): below
//!  ),
//!  inputs: { "pyramid": "depth_pyramid_prev" },     // occlusion culling only: below
//!  outputs: { "samples": "samples",                 // Buffer(per_sample: 8, samples: 4)
//!             "occluded": "occluded" })             // occlusion culling only
//! ```
//!
//! `other_samples: at_edges` stores the keys of samples other than 0 only at pixels whose
//! samples show more than one triangle (sample 0's key says which): `light_tiled` reads
//! no more, and the raster writes a quarter of a 4x buffer away from edges (on the H200
//! at 3840x2160 builtin:dense's 4x raster 0.81 -> 0.79 ms, lights?count=256's 0.47 ->
//! 0.42: docs/design/compute-raster.md, run visibility-runs). Elsewhere those samples hold whatever an
//! earlier frame left: a pass reading every sample (`keys_depth`) needs `everywhere`,
//! the default.
//!
//! The draws' triangles come in clusters of up to 64 (rgraph_scene::cluster, made when
//! the scene is uploaded), which the bins cull and list before any triangle
//! (bin_triangles.wgsl): `clusters: culled` drops those wholly outside the view volume
//! (by their box) and those showing only back faces (by their normal cone), and bins the
//! rest triangle by triangle (the default); `whole` also lists a cluster within the depth
//! planes touching at most 4 tiles once per tile, whose raster sets its triangles up
//! itself, so that binning a dense mesh takes an atomic per cluster and tile, not per
//! triangle and tile; `off` bins every triangle, as before clusters. The image is the same
//! whichever is chosen (tests/culling.rs): culling drops only triangles that cover no
//! sample.
//!
//! With a `pyramid` input, clusters are culled by occlusion too, in two phases of two
//! passes (common/occlusion.rs says how a file writes them): the first (this slot a
//! history) bins the clusters the previous frame's depth pyramid does not hide and lists
//! the others in `occluded`; the second (`samples` and `occluded` in inputs and outputs
//! both) bins those of the listed clusters that the pyramid of what the first drew does not
//! hide, and adds their keys to the first's at the pixels it covers. The first then
//! stores every sample's key whatever `other_samples` says, which the second reads, and
//! the second stores every sample's too. `occlusion: false` (or 0) turns it off (the first
//! lists nothing, the second records nothing); `clusters: off` leaves every cluster to the
//! first. The image is the same as without it (tests/culling.rs).
//!
//! `micro: true` rasterises micro clusters a triangle an invocation, Nanite's way
//! (micro_raster.wgsl), on a device with 64-bit atomic max (wgpu's SHADER_INT64 and
//! SHADER_INT64_ATOMIC_MIN_MAX; elsewhere it is off, and every cluster takes the tile
//! raster): the bins call a cluster micro where it lies within the depth planes and its
//! pixel bounds hold at most `micro_pixels` pixels per triangle, list it for a dispatch
//! that keeps each covered sample's key by `atomicMax`, and mark its tiles, whose keys
//! that dispatch clears first and the tile raster then merges its own triangles' into,
//! flagging pixels of several triangles. Coverage and depths are the tile raster's, so the
//! image is the same, exactly (tests/culling.rs). Needs `clusters: culled` or `whole`; not
//! for the second phase of occlusion culling, which adds to flagged keys (an error).
//!
//! The bins hold a number of slots, the triangles a frame bins one by one (those of the
//! clusters neither culled, micro nor listed whole): by default the scene's opaque
//! triangles up to half a slot per output pixel, at least 2^20
//! (common/gpu/bin_sizes.rs), 168 bytes each, so that their memory follows the output
//! rather than the scene; `binned_triangles` sets the slots (to the scene's count). A
//! frame that needs more takes slower paths for the clusters past them, to the same image
//! (bin_triangles.wgsl): each is listed whole in the tiles it touches where it lies
//! within the depth planes and touches at most 4, else read by every tile, which tests
//! its bounds first.
//!
//! `light_tiled` with a `samples` input shades it as it shades a hardware visibility
//! buffer's `ids` and `depth`, with the same IDs (the triangle's position in the scene's
//! index buffer / 3, + 1) and the same sample positions; triangle_setup.wgsl gives the
//! coverage rules. Depth is reversed-Z (1 near, 0 far), the convention a float depth
//! buffer gets. Alpha MASK draws are tested as the hardware pass tests them: their base
//! colour's alpha times the vertex colour's, times a base colour texture's alpha read
//! from the scene's texture table (group 3, mask_texture.wgsl; compiled out for scenes
//! without textured masks, feature `mask_textures`), at the pixel centre, against the
//! cutoff: a pixel's samples are kept or dropped together, as a discard drops them.
//! Alpha BLEND draws are left out, as with a G-buffer: the transparent pass draws them
//! later, testing against the depth `keys_depth` makes from the keys.

use serde::Deserialize;

use rgraph_core::file::{Plugin, PluginError, Slots};
use rgraph_core::shader::Stage;
use rgraph_core::{Buffer, BufferHandle, BufferRole, PassBuilder, PassKind};

use crate::common::occlusion::{self, OcclusionSlots, Phase};
use crate::common::plugin::{check_tile, Shared};
use crate::common::switch::Switch;
use crate::common::visibility_samples;
use crate::shaders;

pub struct VisibilityCompute(pub(crate) Shared);

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VisibilityComputeParams {
    /// Pixels per tile side.
    #[serde(default = "tile")]
    pub tile: u32,
    #[serde(default)]
    pub other_samples: OtherSamples,
    #[serde(default)]
    pub clusters: Clusters,
    /// Occlusion culling, where the slots ask for it: on unless `false`.
    #[serde(default)]
    pub occlusion: Option<Switch>,
    /// Micro clusters rasterised a triangle an invocation, where the device can: off unless
    /// `true`.
    #[serde(default)]
    pub micro: Option<Switch>,
    /// The most pixels per triangle a micro cluster's pixel bounds hold.
    #[serde(default = "micro_pixels")]
    pub micro_pixels: u32,
    /// The bins' slots, where not the default from the output.
    #[serde(default)]
    pub binned_triangles: Option<u32>,
}

/// How `visibility_compute` culls and bins the draws' clusters.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Clusters {
    /// Culled, and listed whole in the tiles they touch where they are small on screen.
    Whole,
    /// Culled; every triangle of those left binned by itself. The default: `whole` was
    /// measured slower on the H100 (docs/design/compute-raster.md).
    #[default]
    Culled,
    /// Neither: every triangle binned by itself.
    Off,
}

/// Where `visibility_compute` stores the keys of samples other than sample 0.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum OtherSamples {
    /// At every pixel: every sample of the buffer holds its key.
    #[default]
    Everywhere,
    /// Only at pixels whose samples show more than one triangle, which sample 0's key
    /// flags: enough for readers that read the others only there (`light_tiled`).
    AtEdges,
}

fn tile() -> u32 {
    16
}

fn micro_pixels() -> u32 {
    4
}

/// `micro_pixels` allowed: a micro triangle's invocation scans at most its cluster's
/// bounds, 64 triangles' worth of them, which stays far under lavapipe's 65,535 loop
/// iterations an invocation.
const MICRO_PIXELS: std::ops::RangeInclusive<u32> = 1..=16;

/// Tile sides allowed: a workgroup of 16 x 16 invocations is WebGPU's largest.
const TILES: std::ops::RangeInclusive<u32> = 4..=16;

/// The pass as set up: what its `gpu` module records.
#[cfg_attr(not(feature = "gpu"), allow(dead_code))]
pub(crate) struct RasterDispatch {
    pub raster: String,
    pub bins: String,
    pub tile: u32,
    pub clusters: Clusters,
    pub samples: BufferHandle,
    /// raster_tiles.wgsl's OTHERS_EVERYWHERE.
    pub others_everywhere: bool,
    /// The phase of occlusion culling the pass is, if any.
    pub occlusion: Option<OcclusionSlots>,
    /// The micro raster, where the pass asks for it: made where the device can run it.
    pub micro: Option<MicroRaster>,
    /// The bins' slots the pass asks for.
    pub slots: Option<u32>,
}

/// The micro clusters' raster as set up: micro_raster.wgsl composed, and the most pixels
/// per triangle of a micro cluster's bounds (bin_triangles.wgsl's MICRO_PIXELS).
#[cfg_attr(not(feature = "gpu"), allow(dead_code))]
pub(crate) struct MicroRaster {
    pub source: String,
    pub pixels: u32,
}

impl Plugin for VisibilityCompute {
    const NAME: &'static str = "visibility_compute";
    type Params = VisibilityComputeParams;

    fn kind(&self, _: &VisibilityComputeParams) -> PassKind {
        PassKind::Compute
    }

    fn setup(
        &self,
        params: VisibilityComputeParams,
        pass: &mut PassBuilder<'_>,
        slots: &mut Slots<'_>,
    ) -> Result<(), PluginError> {
        check_tile(params.tile, TILES)?;
        // Every key is stored each frame (nothing of an earlier version is read), but by
        // the second phase of occlusion culling, which adds to the first's.
        let modified = slots.modifies("samples");
        let role = BufferRole::Storage {
            read: modified,
            write: true,
        };
        let samples = slots.write::<Buffer>("samples", |t| pass.buffer(t.handle, role))?;
        let count = visibility_samples::sample_count(pass, slots, "samples", samples)?;
        let occlusion = occlusion::take(params.occlusion, modified, pass, slots)?;
        if modified && occlusion.is_none() {
            return Err(PluginError::Slot {
                slot: "samples".into(),
                resource: slots.resource("samples").unwrap_or("samples").to_owned(),
                why: "is in inputs, but only the second phase of occlusion culling (with a \
                      \"pyramid\" input) adds to the keys it reads: list it in outputs only"
                    .into(),
            });
        }
        let culling = occlusion.filter(|o| o.on).map(|o| o.phase);
        let micro = params.micro == Some(Switch::On);
        if micro && !MICRO_PIXELS.contains(&params.micro_pixels) {
            return Err(PluginError::Invalid(format!(
                "micro_pixels must be {} to {}, got {}",
                MICRO_PIXELS.start(),
                MICRO_PIXELS.end(),
                params.micro_pixels
            )));
        }
        if params.binned_triangles == Some(0) {
            return Err(PluginError::Invalid(
                "binned_triangles must be at least 1, got 0".into(),
            ));
        }
        if micro && modified {
            return Err(PluginError::Invalid(
                "micro: true is for a first raster pass: the second phase of occlusion \
                 culling adds to keys already flagged, which 64-bit atomics cannot"
                    .into(),
            ));
        }
        let generated = format!(
            "// Generated: the tile's side in pixels, then the sample lanes.\n\
             const TILE: u32 = {}u;\n{}",
            params.tile,
            shaders::sample_lanes(count)
        );
        let raster = shaders::VISIBILITY_COMPUTE.compose_with(count, &generated)?;
        let micro = match micro {
            true => {
                let shader =
                    shaders::MICRO_RASTER.compose_for(count, &generated, shaders::INT64_ATOMICS)?;
                Some(MicroRaster {
                    source: shader.source().to_owned(),
                    pixels: params.micro_pixels,
                })
            }
            false => None,
        };
        let Some(entry) = raster.entry("cs_raster_tiles", Stage::Compute) else {
            return Err(PluginError::Invalid(
                "raster_tiles.wgsl has no entry point cs_raster_tiles".into(),
            ));
        };
        pass.workgroup(entry.workgroup());
        // The bins' culling by occlusion: the first phase lists nothing where it is off,
        // but clears the list the second reads.
        let culls_by = match occlusion.map(|o| o.phase) {
            None => shaders::OCCLUSION_NONE,
            Some(Phase::First) => shaders::OCCLUSION_FIRST,
            Some(Phase::Second) => shaders::OCCLUSION_SECOND,
        };
        let dispatch = RasterDispatch {
            raster: raster.source().to_owned(),
            bins: shaders::TILE_BINS
                .compose_with(count, culls_by)?
                .source()
                .to_owned(),
            tile: params.tile,
            clusters: params.clusters,
            samples,
            // Both phases store every sample's key: the second reads them, and adds to
            // them where it covers a pixel.
            others_everywhere: params.other_samples == OtherSamples::Everywhere
                || culling.is_some(),
            occlusion,
            micro,
            slots: params.binned_triangles,
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

    use super::{Clusters, RasterDispatch};
    use crate::common::gpu::occlusion::OcclusionGroup;
    use crate::common::gpu::pipeline::{module, pipeline_layout};
    use crate::common::gpu::storage::{storage_group, storage_layout};
    use crate::common::gpu::tile_bins::{
        Binning, ClusterBinning, TileBins, MICRO_ARGS_OFFSET, RASTER_BUFFERS,
    };
    use crate::common::gpu::{compute_pipeline, Compute, Frame, Recorded, Recorder};
    use crate::common::occlusion::Phase;
    use crate::common::visibility_samples::fits_binding;
    use crate::gpu_scene::GpuScene;
    use crate::shaders::INT64_ATOMICS;
    use crate::variant::GatedShader;
    use rgraph_scene::DepthConvention;

    pub(crate) struct State {
        layout: wgpu::BindGroupLayout,
        raster: wgpu::ComputePipeline,
        /// The bins and the output size they were made for (or why the device cannot
        /// hold them).
        bins: Option<((u32, u32), Result<TileBins, String>)>,
        /// The bins' group 3, for a phase of occlusion culling.
        occlusion: Option<OcclusionGroup>,
        /// The micro raster's clear and raster, where the pass asks for it and the device
        /// has 64-bit atomic max.
        micro: Option<MicroPipelines>,
    }

    struct MicroPipelines {
        clear: wgpu::ComputePipeline,
        raster: wgpu::ComputePipeline,
        /// The most pixels per triangle of a micro cluster's bounds.
        pixels: u32,
    }

    impl Recorder for RasterDispatch {
        type Stage = Compute;
        type Scene = Arc<GpuScene>;
        type State = State;

        fn build(&self, frame: &Frame<'_, '_, Self>) -> Result<State, String> {
            let (device, scene) = (frame.device, &frame.scene);
            // The keys, then the bins.
            let mut read_only = vec![false];
            read_only.extend([true; RASTER_BUFFERS]);
            let layout = storage_layout(device, "visibility_compute", &read_only);
            let raster_module = module(device, "visibility_compute", &self.raster);
            let pipeline_layout = pipeline_layout(
                device,
                &[
                    Some(scene.layout()),
                    Some(&layout),
                    Some(scene.geometry_layout()),
                    Some(scene.texture_table_layout()),
                ],
            );
            let second = self.occlusion.is_some_and(|o| o.phase == Phase::Second);
            let variant = frame
                .scenes
                .variant(GatedShader::VisibilityRaster)
                .constants();
            // Off where the device cannot: every cluster takes the tile raster.
            let micro = (self.micro.as_ref())
                .filter(|_| device.features().contains(INT64_ATOMICS))
                .map(|micro| {
                    let micro_module = module(device, "visibility_compute: micro", &micro.source);
                    let pipeline = |entry: &str| {
                        let label = "visibility_compute: micro";
                        compute_pipeline(
                            device,
                            label,
                            &pipeline_layout,
                            &micro_module,
                            entry,
                            &variant,
                        )
                    };
                    MicroPipelines {
                        clear: pipeline("cs_micro_clear"),
                        raster: pipeline("cs_micro_raster"),
                        pixels: micro.pixels,
                    }
                });
            let mut constants = vec![
                (
                    "OTHERS_EVERYWHERE",
                    f64::from(u8::from(self.others_everywhere)),
                ),
                ("MERGE", f64::from(u8::from(second))),
                ("MICRO", f64::from(u8::from(micro.is_some()))),
            ];
            constants.extend(variant);
            let raster = compute_pipeline(
                device,
                "visibility_compute",
                &pipeline_layout,
                &raster_module,
                "cs_raster_tiles",
                &constants,
            );
            Ok(State {
                layout,
                raster,
                bins: None,
                occlusion: self.occlusion.map(|o| OcclusionGroup::new(device, o.phase)),
                micro,
            })
        }

        fn record(&self, state: &mut State, frame: &mut Frame<'_, '_, Self>) -> Recorded {
            let pass = &mut *frame.pass;
            let (resources, device, scene) = (frame.resources, frame.device, &frame.scene);
            let size = resources.output_size();
            let occlusion = match (self.occlusion, state.occlusion.as_mut()) {
                // Off: the first phase listed nothing.
                (Some(o), _) if o.phase == Phase::Second && !o.on => return Ok(()),
                (Some(o), Some(group)) => {
                    // The first phase tests where culling is on and the previous frame's
                    // pyramid holds a frame.
                    let test = o.on
                        && self.clusters != Clusters::Off
                        && !(o.phase == Phase::First && resources.history_reset(o.pyramid));
                    let bound = (resources.view(o.pyramid), resources.buffer(o.occluded));
                    let camera = &scene.inputs().camera;
                    let seen = (resources.frame(), camera, size);
                    Some(group.group(device, resources.queue, bound, seen, test))
                }
                _ => None,
            };
            // The bins are made for one output size: a resized graph gets new ones.
            if state.bins.as_ref().is_some_and(|(made, _)| *made != size) {
                state.bins = None;
            }
            let (_, bins) = state.bins.get_or_insert_with(|| {
                let binning = Binning {
                    tile: self.tile,
                    clusters: ClusterBinning {
                        cull: self.clusters != Clusters::Off,
                        whole: self.clusters == Clusters::Whole,
                        micro: state.micro.as_ref().map_or(0, |m| m.pixels),
                    },
                    slots: self.slots,
                    occlusion: state.occlusion.as_ref().map(|o| &o.layout),
                };
                let bins = TileBins::new(device, &self.bins, scene, &binning, size);
                (size, bins)
            });
            let bins = bins.as_ref().map_err(String::clone)?;
            bins.buffers()
                .iter()
                .chain(state.occlusion.as_ref().and_then(OcclusionGroup::buffer))
                .for_each(|buffer| resources.hold(buffer));
            let geometry = scene.geometry_group(device)?;
            // Textured alpha masks read the table.
            let table = frame.scenes.texture_table(scene, device, resources.queue)?;
            let keys = resources.buffer(self.samples);
            fits_binding(device, keys)?;
            let mut buffers = vec![keys];
            buffers.extend(bins.raster_buffers());
            let group = storage_group(device, "visibility_compute", &state.layout, &buffers);
            bins.record(pass, scene, geometry, occlusion.as_ref());
            pass.set_bind_group(0, scene.bind_group(DepthConvention::ReversedZ), &[]);
            pass.set_bind_group(1, &group, &[]);
            pass.set_bind_group(2, geometry, &[]);
            pass.set_bind_group(3, table, &[]);
            let tiles = (size.0.div_ceil(self.tile), size.1.div_ceil(self.tile));
            if let Some(micro) = &state.micro {
                pass.set_pipeline(&micro.clear);
                pass.dispatch_workgroups(tiles.0, tiles.1, 1);
                pass.set_pipeline(&micro.raster);
                pass.dispatch_workgroups_indirect(bins.dispatch_args(), MICRO_ARGS_OFFSET);
            }
            pass.set_pipeline(&state.raster);
            pass.dispatch_workgroups(tiles.0, tiles.1, 1);
            Ok(())
        }
    }
}
