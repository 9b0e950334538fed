//! `light_tiled`: lighting and resolve in one compute pass, by tiles (Lauritzen,
//! "Deferred Rendering for Current and Future Rendering Pipelines", SIGGRAPH 2010): the
//! fast path beside the fragment light passes, which stay as the seeds' method and the
//! baseline.
//!
//! ```ron
//! (name: "light", plugin: "light_tiled",
//!  params: (
//!      edges: (detector: compare),   // common/edge_detection.rs: the same
//!                                    // detectors and thresholds as edge_stencil
//!      shading: per_sample,          // or adaptive: each fragment once; or
//!                                    // surfaces: each smooth surface once
//!      resolve: box, exposure: 1.0,  // or resolve: tonemapped (resolve.rs)
//!      tile: 16,                     // pixels per tile side
//!      cull: true,                   // false: every light in every tile
//!      view: shaded,                 // or edges | tile_lights | fragments | shadows
//!                                    // | cascades
//!  ),                                // (these are the defaults)
//!  inputs: {
//!      "albedo": "albedo", "normal": "normal", "material": "material",
//!      "view_depth": "view_depth",
//!      "depth": "depth",   // the G-buffer's depth(-stencil): its depth aspect is read
//!      "hdr": "hdr",       // emission and unlit colour, per sample
//!      "ao": "ao",         // optional: ssao_blur's occlusion (r8unorm, 1 sample),
//!                          // which scales the ambient and environment light only
//!      "shadows": "shadow_atlas",  // optional: shadow_maps's atlas (depth32float),
//!                          // which scales each shadowed light (common/shadows.rs)
//!  },
//!  outputs: { "resolved": "resolved" })   // 1 sample, rgba16float, storage
//! ```
//!
//! # The G-buffer's layout
//!
//! The pass reads what its file binds, and composes the shader to match:
//! - without `view_depth` (the lean G-buffer), view depth comes from the depth buffer,
//!   each sample's unprojected at its position, and a non-edge pixel is shaded at the
//!   mean of its samples' positions and depths (the pixel centre, on the surface);
//! - for what samples emit, `hdr` (rgba16float), or `emission` (RGB9E5 in rg16uint, the
//!   lean G-buffer's, plus an unlit surface's colour from albedo), or neither (a scene
//!   that emits nothing: unlit colour from albedo, and the `background` parameter, black
//!   by default, where nothing was drawn);
//! - `ids` instead of albedo, normal, material, view depth and emission: a visibility
//!   buffer (passes/visibility.rs). Each pixel's distinct triangles are rebuilt from the
//!   scene's geometry (group 2) and their materials sampled from the scene's texture
//!   table (group 3, made on the first frame: GpuScene::texture_table_group), edge pixels
//!   are those whose samples show different triangles, and
//!   `shading: adaptive` shades each triangle once, exactly, and `shading: surfaces`
//!   each smooth surface once: the triangles of one mesh that share a vertex with a
//!   normal, lie within the `compare` detector's depth threshold of each other at the
//!   pixel and bend by less than 8 degrees are one fragment, each rebuilt at its own samples and their surfaces averaged
//!   for one lighting, so that a dense mesh's pixels are not edges for its triangles
//!   alone (visibility_read.wgsl's smooth_join and joined_gsample;
//!   pipelines/visibility_msaa_4x.ron on CPU adapters);
//! - `samples` instead of `ids` and `depth`: a visibility buffer rasterised in compute
//!   (passes/visibility_compute.rs), depth and ID per sample in one graph buffer (group 1,
//!   binding 8), whose size gives the sample count (pipelines/visibility_msaa_4x.ron on
//!   GPUs).
//!
//! One workgroup of `tile` x `tile` invocations per tile, one per pixel
//! (light_tiled.wgsl says how): it classifies each pixel as edge or not with
//! [`EdgeDetection`], culls point and spot lights against the tile's side planes and
//! depth bounds in batches of one light per invocation (so any number of lights is
//! correct), shades non-edge pixels once and the other samples (or, with `adaptive`,
//! the other fragments, weighted by the samples they cover: seed 002) of edge
//! pixels as a workgroup list dealt out from the first invocation on, and
//! resolves into the single-sampled output.
//! No multisampled HDR accumulation, no stencil, no resolve pass.
//! A visibility buffer shaded at more than one sample per pixel knows its edge pixels
//! from one flag or ID comparison: the tiles' dispatch lists them into a buffer the pass
//! owns (4 bytes a pixel of the output, which frames report as the pass's own) and leaves
//! them out; a second dispatch lights them in runs of 128 listed pixels, each pixel an
//! invocation's, its fragments in turn, and resolves them (light_edges_listed.wgsl;
//! docs/design/compute-raster.md, run visibility-edges says why). A run culls lights for itself as a tile
//! does where the scene has more than 8 point and spot lights; with fewer each fragment
//! tests every light, which costs less than the run's culling.
//!
//! The workgroup memory the shader needs grows with the tile and the sample count
//! (`tile`² x (samples − 1) edge entries of 16 bytes where the tile lights its edge
//! pixels): the graph checks it against the device profile when compiling, so a tile
//! too big for a device (16 at 8x against the WebGPU default of 16 KiB) is an error
//! naming the pass, and `tile: 8` fits.
//!
//! Debug views write an `rgba8unorm` output named `color` instead of `resolved`:
//! `edges` (red edge pixels, blue others, black without geometry, as debug_view's),
//! `tile_lights` (lights each tile shades, directional ones included, as a heat map from
//! blue for 1 to red for 64 or more), `fragments` (fragments per pixel: dark
//! grey 1, green 2, blue 3, red 4 or more), `shadows` (the visibility term of the
//! most important shadowed light, from the `shadows` input: white lit, black shadowed)
//! and `cascades` (the first shadowed directional light's cascade at each pixel: red,
//! green, blue, yellow from the nearest, grey past the last, darker in its shadow).

use serde::Deserialize;

use rgraph_core::file::{Plugin, PluginError, Slots};
use rgraph_core::shader::{Shader, Stage};
use rgraph_core::types::TextureFormat;
use rgraph_core::{Aspect, BufferHandle, PassBuilder, PassKind, TextureHandle};

use super::resolve::{one, resolve_exposure, ResolveMode};
use crate::common::ao;
use crate::common::depth::DepthRule;
use crate::common::edge_detection::{Detector, EdgeDetection};
use crate::common::gbuffer_layers::LayerSet;
use crate::common::gbuffer_layout::{GBufferLayout, Surfaces};
use crate::common::plugin::{check_tile, yes, Shared};
use crate::common::shadows;
use crate::common::textures::{self, format_name, Input, Texels, Want};
use crate::common::visibility_samples;
use crate::shaders;
use crate::shadows::ShadowFilter;

pub struct LightTiled(pub(crate) Shared);

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LightTiledParams {
    #[serde(default)]
    pub edges: EdgeDetection,
    #[serde(default)]
    pub shading: EdgeShading,
    #[serde(default)]
    pub resolve: ResolveMode,
    #[serde(default = "one")]
    pub exposure: f32,
    #[serde(default = "tile")]
    pub tile: u32,
    #[serde(default = "yes")]
    pub cull: bool,
    #[serde(default)]
    pub view: TiledView,
    /// What samples where nothing was drawn resolve to, when the G-buffer has neither
    /// `hdr` nor `emission` (which are cleared to the G-buffer pass's background).
    #[serde(default)]
    pub background: Option<[f64; 3]>,
}

fn tile() -> u32 {
    16
}

/// How `light_tiled` shades an edge pixel.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum EdgeShading {
    /// Every sample (seed 000's per-sample shading).
    #[default]
    PerSample,
    /// Each fragment among the samples once, weighted by the samples it covers (seed
    /// 002's adaptive shading by unique fragments): samples whose G-buffer values are
    /// identical are one fragment, as the G-buffer pass shades once per pixel and
    /// triangle.
    Adaptive,
    /// As `adaptive`, and where the pass reads a visibility buffer, samples of different
    /// triangles of one smooth surface are one fragment too (visibility_read.wgsl's
    /// smooth_join): at most one shading per surface a pixel shows, however dense its
    /// triangles. A G-buffer's fragments are as `adaptive` finds them (its samples hold
    /// no triangles to join).
    Surfaces,
}

/// What `light_tiled` writes.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TiledView {
    /// The lit, resolved HDR image.
    #[default]
    Shaded,
    Edges,
    TileLights,
    Fragments,
    /// The shadow maps' visibility term of the most important shadowed light (its share
    /// of the filter's taps that see the surface, white lit to black shadowed) at each
    /// pixel's sample 0; needs the `shadows` input.
    Shadows,
    /// Which cascade of the first shadowed directional light holds each pixel's sample 0
    /// (red, green, blue, yellow from the nearest; grey past the last or without such a
    /// light), darker where the light is shadowed; needs the `shadows` input.
    Cascades,
}

impl TiledView {
    /// light_tiled.wgsl's `VIEW`.
    fn constant(self) -> f64 {
        match self {
            TiledView::Shaded => 0.0,
            TiledView::Edges => 1.0,
            TiledView::TileLights => 2.0,
            TiledView::Fragments => 3.0,
            TiledView::Shadows => 4.0,
            TiledView::Cascades => 5.0,
        }
    }

    /// The output slot and the formats it may have: storage formats.
    fn output(self) -> (&'static str, Want) {
        const VIEW: &[TextureFormat] = &[TextureFormat::Rgba8Unorm];
        match self {
            TiledView::Shaded => (
                "resolved",
                Want::new("the resolved HDR target", textures::HDR),
            ),
            _ => ("color", Want::new("a debug view", VIEW)),
        }
    }
}

/// Where the pass reads its samples' depth.
#[derive(Copy, Clone)]
#[cfg_attr(not(feature = "gpu"), allow(dead_code))]
pub(crate) enum Depth {
    /// A depth buffer (group 1, binding 5), in the convention its format gets.
    Buffer(DepthRule, TextureHandle),
    /// A compute rasteriser's keys (group 3): reversed-Z, and the triangles rebuilt from
    /// the scene's geometry.
    Keys(BufferHandle),
}

/// The entry point lighting every pixel that is not an edge pixel, and every pixel of a
/// debug view or of a single-sampled output.
const PIXELS: &str = "cs_light_tiled";
/// The entry points emptying the list of edge pixels before it and lighting them after
/// it (light_edges_listed.wgsl).
const EDGES_RESET: &str = "cs_edge_pixels_reset";
const EDGES: &str = "cs_light_edge_pixels";

/// The workgroups lighting the listed edge pixels, each going through the list's runs in
/// turn: on a GPU enough to fill a large one (4096 x 128 invocations; 2048 measured
/// 0.02 ms slower on the H200, 8192 the same: docs/design/compute-raster.md, run visibility-merged); on a
/// CPU, which runs workgroups one after another on its threads and pays for each,
/// CPU_EDGE_WORKGROUPS
/// (lavapipe's tiled pass of visibility_msaa_4x on dense at 640x360: 211 ms with 4096,
/// 113-123 with 64, about the same with 16 or 256).
#[cfg(feature = "gpu")]
fn edge_workgroups(device: &wgpu::Device) -> u32 {
    match device.adapter_info().device_type {
        wgpu::DeviceType::Cpu => CPU_EDGE_WORKGROUPS,
        _ => 4096,
    }
}
#[cfg(feature = "gpu")]
const CPU_EDGE_WORKGROUPS: u32 = 64;
/// Where light_edges_listed.wgsl binds the list of edge pixels in group 1.
#[cfg_attr(not(feature = "gpu"), allow(dead_code))]
const EDGE_PIXELS_BINDING: u32 = 12;

/// Tile sides allowed: the four side planes are set up by four invocations, and 32 x 32
/// invocations is more than any device's workgroup.
const TILES: std::ops::RangeInclusive<u32> = 2..=32;

/// The tiled pass as set up: what its `gpu` module records.
#[cfg_attr(not(feature = "gpu"), allow(dead_code))]
pub(crate) struct TiledDispatch {
    pub source: String,
    /// The entry points dispatched, in order, over the same tiles and bindings.
    pub entries: Vec<&'static str>,
    pub constants: Vec<(&'static str, f64)>,
    /// The shader takes view depth from the depth buffer and needs the convention's
    /// `FAR_DEPTH` (view_depth_from_depth.wgsl).
    pub view_depth_from_depth: bool,
    /// A raster pass's visibility buffer's IDs: the shader rebuilds their triangles from
    /// the scene's geometry (group 2).
    pub ids: Option<TextureHandle>,
    pub tile: u32,
    pub depth: Depth,
    pub output: TextureHandle,
    pub inputs: Vec<Input>,
}

impl Plugin for LightTiled {
    const NAME: &'static str = "light_tiled";
    type Params = LightTiledParams;

    fn kind(&self, _: &LightTiledParams) -> PassKind {
        PassKind::Compute
    }

    fn setup(
        &self,
        params: LightTiledParams,
        pass: &mut PassBuilder<'_>,
        slots: &mut Slots<'_>,
    ) -> Result<(), PluginError> {
        params.edges.check()?;
        check_tile(params.tile, TILES)?;
        let exposure = resolve_exposure(&self.0, params.exposure, params.resolve)?;
        let layout = GBufferLayout::of(slots, params.background)?;
        let mut inputs = Vec::new();
        let (depth, samples) = match layout.surfaces {
            Surfaces::VisibilitySamples => {
                let (keys, samples) = visibility_samples::read(pass, slots, "samples")?;
                (Depth::Keys(keys), samples)
            }
            Surfaces::GBuffer | Surfaces::VisibilityTextures => {
                let want = Want::new("the G-buffer's depth", textures::DEPTH_ANY);
                let (depth, desc) = textures::input(slots, pass, "depth", want)?;
                pass.sampled_aspect(depth, Aspect::DepthOnly);
                inputs.push(Input {
                    binding: 5,
                    texture: depth,
                    aspect: Aspect::DepthOnly,
                    texels: Texels::Depth,
                });
                (Depth::Buffer(DepthRule::new(None), depth), desc.samples)
            }
        };
        if layout.surfaces.visibility() && params.edges.detector != Detector::Compare {
            return Err(PluginError::Invalid(
                "a visibility buffer's edge pixels are those whose samples show different \
                 triangles: leave out edges' detector"
                    .into(),
            ));
        }
        let (visibility_ids, layers) = layout.bind(slots, pass, samples, &mut inputs)?;
        let (slot, want) = params.view.output();
        let (output, out) = textures::output(slots, pass, slot, want.samples(1), |pass, h, _| {
            pass.storage_write(h)
        })?;
        inputs.push(Input {
            binding: 7,
            texture: output,
            aspect: Aspect::All,
            texels: Texels::Store,
        });
        // A visibility buffer shaded at more than one sample per pixel has its edge
        // pixels listed and lit by a dispatch of their own (light_edges_listed.wgsl); a
        // G-buffer's are classified from every sample's channels, too much to read twice,
        // and stay in their tile, as do a debug view's.
        let listed =
            samples > 1 && params.view == TiledView::Shaded && layout.surfaces.visibility();
        // The tile's edge-list entries: every sample of every pixel but one, where the
        // tile lights its edge pixels.
        let capacity = match samples > 1 && !listed {
            true => params.tile * params.tile * (samples - 1),
            false => 1,
        };
        // The shader's sizes are constants, so the workgroup memory the compile checks
        // is the memory this tile and sample count use.
        let head = format!(
            "// Generated: the tile, its edge-list entries, the output, then the G-buffer's\n\
             // layout and where edge pixels are lit.\n\
             const TILE: u32 = {}u;\n\
             const EDGE_CAPACITY: u32 = {capacity}u;\n\
             alias OutTex = texture_storage_2d<{}, write>;\n",
            params.tile,
            format_name(out.format),
        );
        let edges = match listed {
            true => shaders::LIGHT_EDGES_LISTED,
            false => shaders::EDGES_IN_TILES,
        };
        let ao = ao::input(slots, pass)?;
        inputs.extend(ao);
        let shadows = shadows::input(slots, pass)?;
        let needs_shadows = match params.view {
            TiledView::Shadows => Some("view: shadows shows the shadow maps' visibility term"),
            TiledView::Cascades => Some("view: cascades shows the directional light's cascades"),
            _ => None,
        };
        if let (Some(what), None) = (needs_shadows, &shadows) {
            return Err(PluginError::Invalid(format!(
                "{what}: give the pass a \"shadows\" input (the shadow_maps pass's atlas)"
            )));
        }
        let entries = match listed {
            true => vec![EDGES_RESET, PIXELS, EDGES],
            false => vec![PIXELS],
        };
        let detector = match params.edges.detector {
            _ if layout.surfaces.visibility() => 4.0,
            Detector::Compare => 0.0,
            Detector::Centroid | Detector::Coverage => 1.0,
            Detector::All => 2.0,
            Detector::None => 3.0,
        };
        let mut constants = params.edges.constants();
        constants.extend([
            ("DETECTOR", detector),
            (
                "ADAPTIVE",
                f64::from(u8::from(params.shading != EdgeShading::PerSample)),
            ),
            ("CULL", f64::from(u8::from(params.cull))),
            ("VIEW", params.view.constant()),
            (
                "RESOLVE",
                f64::from(u8::from(params.resolve == ResolveMode::Tonemapped)),
            ),
            ("EXPOSURE", f64::from(exposure)),
        ]);
        if layout.surfaces.visibility() {
            constants.push((
                "SMOOTH_SURFACES",
                f64::from(u8::from(params.shading == EdgeShading::Surfaces)),
            ));
        }
        let view_depth_from_depth = !layout.stored_view_depth;
        let source = TiledSource {
            head,
            layout,
            tail: edges.to_owned() + &ao::wgsl(ao.as_ref()),
            filter: self.0.overrides.shadows.filter,
            samples,
        };
        // The device must allow each entry point's workgroup: the same with or without
        // the atlas and the layers, whose textures take no workgroup memory.
        let all = LayerSet::all(&layers);
        for atlas in [shadows.as_ref(), None] {
            let shader = source.compose(all, atlas)?;
            for name in &entries {
                let Some(entry) = shader.entry(name, Stage::Compute) else {
                    return Err(PluginError::Invalid(format!(
                        "light_tiled.wgsl has no entry point {name}"
                    )));
                };
                pass.workgroup(entry.workgroup());
            }
        }
        let optional_atlas = shadows::optional(slots);
        let targets = layers.clone();
        let make = move |set: LayerSet| {
            shadows::variants(optional_atlas, shadows, |atlas| {
                let mut inputs = set.inputs(&targets, &inputs);
                inputs.extend(atlas.copied());
                Ok(TiledDispatch {
                    source: source.compose(set, atlas)?.source().to_owned(),
                    entries: entries.clone(),
                    constants: constants.clone(),
                    view_depth_from_depth,
                    ids: visibility_ids,
                    tile: params.tile,
                    depth,
                    output,
                    inputs,
                })
            })
        };
        self.0.record_kept(pass, layers, make)
    }
}

/// The tiled pass's shader but for the material layers its G-buffer holds in a frame and
/// the shadow atlas: the generated block's head (tile, edge list, output), the G-buffer's
/// layout and its tail (where edge pixels are lit, the ambient occlusion).
struct TiledSource {
    head: String,
    layout: GBufferLayout,
    tail: String,
    filter: ShadowFilter,
    samples: u32,
}

impl TiledSource {
    fn compose(&self, layers: LayerSet, atlas: Option<&Input>) -> Result<Shader, PluginError> {
        let generated = format!(
            "{}{}{}{}",
            self.head,
            self.layout.wgsl(layers),
            self.tail,
            shadows::wgsl(atlas, 1, self.filter)
        );
        shaders::LIGHT_TILED.compose_with(self.samples, &generated)
    }
}

#[cfg(feature = "gpu")]
mod gpu {
    //! Recording the tiled light pass: one dispatch of a workgroup per tile over the output,
    //! its pipeline compiled for the scene's light kinds (variant.rs) and the depth
    //! format's convention, made on first use and kept.

    use std::sync::Arc;

    use super::{edge_workgroups, Depth, TiledDispatch, EDGES, EDGES_RESET, EDGE_PIXELS_BINDING};
    use crate::common::depth::far_depth;
    use crate::common::gpu::storage::scratch;
    use crate::common::gpu::{compute_pipeline, split_ids, Compute, Frame, GroupBuffers, Recorded};
    use crate::common::gpu::{InputPass, Recorder};
    use crate::common::visibility_samples::{fits_binding, KEYS_BINDING};
    use crate::gpu_scene::GpuScene;
    use crate::variant::{GatedShader, Variant};
    use rgraph_scene::DepthConvention;

    #[derive(Clone, PartialEq)]
    pub(crate) struct Key {
        convention: DepthConvention,
        variant: Variant,
        /// The visibility buffer's ID format.
        ids: Option<wgpu::TextureFormat>,
    }

    pub(crate) struct State {
        pass: InputPass<Key, Vec<wgpu::ComputePipeline>>,
        /// The list of edge pixels, where they are listed, and the output size it was
        /// made for: a count and 4 bytes a pixel.
        edge_list: Option<((u32, u32), wgpu::Buffer)>,
        /// The device's edge_workgroups.
        edge_groups: u32,
    }

    impl TiledDispatch {
        /// Whether edge pixels are listed for a dispatch of their own (which then needs
        /// the list bound and filled).
        fn lists_edges(&self) -> bool {
            self.entries.contains(&EDGES)
        }

        /// Whether it shades a visibility buffer, reading the scene's geometry and
        /// texture table.
        fn visibility(&self) -> bool {
            self.ids.is_some() || matches!(self.depth, Depth::Keys(_))
        }

        /// The storage buffers group 1 holds besides the textures: the keys, if any, and
        /// the list of edge pixels where they are lit apart.
        fn group_buffers(&self) -> GroupBuffers {
            GroupBuffers {
                read: match self.depth {
                    Depth::Keys(keys) => vec![(KEYS_BINDING, keys)],
                    Depth::Buffer(..) => Vec::new(),
                },
                owned: match self.lists_edges() {
                    true => vec![EDGE_PIXELS_BINDING],
                    false => Vec::new(),
                },
            }
        }
    }

    impl Recorder for TiledDispatch {
        type Stage = Compute;
        type Scene = Arc<GpuScene>;
        type State = State;

        fn build(&self, frame: &Frame<'_, '_, Self>) -> Result<State, String> {
            Ok(State {
                pass: InputPass::with_geometry(
                    frame.resources,
                    "light_tiled",
                    &self.source,
                    Some(&frame.scene),
                    &self.inputs,
                    &self.group_buffers(),
                    self.visibility(),
                ),
                edge_list: None,
                edge_groups: edge_workgroups(frame.device),
            })
        }

        fn record(&self, state: &mut State, frame: &mut Frame<'_, '_, Self>) -> Recorded {
            let pass = &mut *frame.pass;
            let (resources, device, scene) = (frame.resources, frame.device, &frame.scene);
            let visibility = self.visibility();
            // What a visibility buffer's shading binds besides its inputs (the scene's
            // geometry and texture table), or why the device cannot.
            let visibility_groups = match visibility {
                false => None,
                true => Some((
                    scene.geometry_group(device)?,
                    frame.scenes.texture_table(scene, device, resources.queue)?,
                )),
            };
            if let Depth::Keys(keys) = self.depth {
                fits_binding(device, resources.buffer(keys))?;
            }
            let convention = match self.depth {
                Depth::Buffer(rule, depth) => rule.convention(resources.shape(depth).format),
                Depth::Keys(_) => DepthConvention::ReversedZ,
            };
            let key = Key {
                convention,
                // Reading a visibility buffer it samples textures itself: without them in
                // the scene their code is compiled out (compiled in, it made lavapipe's
                // 4x shading of builtin:dense about three times slower).
                variant: frame.scenes.variant(match visibility {
                    true => GatedShader::LightTiledVisibility,
                    false => GatedShader::LightTiled,
                }),
                ids: self.ids.map(|ids| resources.shape(ids).format),
            };
            let (module, layout) = (&state.pass.module, &state.pass.layout);
            let pipelines = state.pass.pipelines.get(key, |key| {
                let mut constants = self.constants.clone();
                constants.extend(key.variant.constants());
                if self.view_depth_from_depth {
                    constants.push(("FAR_DEPTH", f64::from(far_depth(key.convention))));
                }
                if let Some(ids) = key.ids {
                    constants.push(("SPLIT_IDS", split_ids(ids)));
                }
                let pipeline = |entry| {
                    compute_pipeline(device, "light_tiled", layout, module, entry, &constants)
                };
                self.entries.iter().copied().map(pipeline).collect()
            });
            pass.set_bind_group(0, scene.bind_group(convention), &[]);
            let out = resources.shape(self.output);
            let mut owned = Vec::new();
            if self.lists_edges() {
                let size = (out.width, out.height);
                let edge_list = &mut state.edge_list;
                if edge_list.as_ref().is_some_and(|(made, _)| *made != size) {
                    *edge_list = None;
                }
                let bytes = 4 + 4 * u64::from(out.width) * u64::from(out.height);
                let label = "light_tiled edge pixels";
                let (_, list) =
                    edge_list.get_or_insert_with(|| (size, scratch(device, label, bytes)));
                resources.hold(list);
                owned.push(&*list);
            }
            let group = state.pass.inputs.bind_group_with(resources, &owned);
            pass.set_bind_group(1, &group, &[]);
            if let Some((geometry, table)) = visibility_groups {
                pass.set_bind_group(2, geometry, &[]);
                pass.set_bind_group(3, table, &[]);
            }
            // wgpu orders the dispatches (the list is written by one and read by the
            // next); they write disjoint pixels of the output.
            for (entry, pipeline) in self.entries.iter().zip(pipelines) {
                pass.set_pipeline(pipeline);
                let (x, y) = match *entry {
                    EDGES_RESET => (1, 1),
                    EDGES => (state.edge_groups, 1),
                    _ => (
                        out.width.div_ceil(self.tile),
                        out.height.div_ceil(self.tile),
                    ),
                };
                pass.dispatch_workgroups(x, y, 1);
            }
            Ok(())
        }
    }
}
