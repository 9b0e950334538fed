//! `gbuffer`: draws the host's scene into the (multisampled) G-buffer.
//!
//! ```ron
//! (name: "gbuffer", plugin: "gbuffer",
//!  params: (background: (0.0, 0.0, 0.0, 1.0)),   // the default; reversed_z optional
//!  outputs: {
//!      "albedo": "albedo",          // rgba8unorm(-srgb): base color
//!      "normal": "normal",          // rg16float: octahedral world-space normal
//!      "material": "material",      // rgba8unorm: metallic, roughness, flags, edge bits
//!      "view_depth": "view_depth",  // r32float: linear view depth, 0 where nothing was drawn
//!      "hdr": "hdr",                // rgba16float: emission and unlit color, else background
//!      "depth": "depth",            // depth24plus-stencil8 or depth32float-stencil8
//!      "mesh": "mesh",              // rg16uint: the mesh index + 1 (optional, see below)
//!      "pose_offset": "pose_offset",// rgba16float: a deformed point's last pose (see below)
//!      "specular": "specular",      // the material layers (optional, see below):
//!      "clearcoat": "clearcoat",    //   rgba8unorm, rg8unorm or rgba16float,
//!      "sheen": "sheen",            //   rgba8unorm
//!  },
//!  optional: ["specular", "clearcoat", "sheen", "pose_offset"])
//! ```
//!
//! All must have the depth's sample count; 1 works too. The full G-buffer's color
//! targets cost 32 bytes per sample (8 + 4 + 8 + 4 + 8 in wgpu's accounting), the WebGPU
//! default limit. Every channel but `albedo` may be left out, and then is not written:
//! - `normal` and `material`: only lighting reads them, so a pipeline's G-buffer pass for
//!   unlit-only scenes (under a `when: "unlit_only"` condition,
//!   pipelines/deferred_msaa_4x.ron) goes without.
//! - `view_depth` exists because the fragment light passes attach the depth-stencil and so
//!   cannot sample its depth aspect while they write the stencil (notes/wgpu30.md); the
//!   tiled compute pass reads the depth buffer instead.
//! - `hdr`, or instead the lean `"emission": "emission"` (`rg16uint`, RGB9E5: 4 bytes for
//!   the 8 of rgba16float), which holds only the emission: the tiled pass takes an unlit
//!   surface's color from albedo and the background from its own parameter. A scene
//!   without emission needs neither.
//! - `mesh`, optional: which mesh each sample shows, so that
//!   [`motion_vectors`](super::motion_vectors) moves a moving object's pixels with it (a
//!   G-buffer holds no object otherwise). Its index + 1 split over rg16uint (low half in
//!   red), 0 where no mesh drew: 4 bytes per sample, which only a pipeline with a temporal
//!   filter pays (pipelines/msaa_4x_taa.ron).
//! - `pose_offset`, optional: where the point each sample holds was in the last pose of
//!   its mesh's skin or morph targets, from where it is, so that the motion vectors move
//!   a deformed surface with its vertices ([`pose_offset`](crate::common::pose_offset)):
//!   8 bytes per sample, which the TAA presets pay only for a scene with deformations
//!   (feature `deformed`) on a device allowing more than 32 bytes per sample, the slot
//!   listed `optional`. Where the plan keeps it, the vertex stage reads the deformation's
//!   replaced positions (group 3).
//! - `specular`, `clearcoat`, `sheen`: KHR_materials_ior and _specular's F0 and weight, the
//!   clear coat's strength, roughness and (rgba16float) normal, the sheen's colour and
//!   roughness (common/gbuffer_layers.rs has the formats, gbuffer_layers.wgsl the
//!   encodings), after every other channel. The shipped pipelines declare each under its
//!   scene feature and list the slots `optional`, so that only a scene whose materials
//!   use a layer pays its 2 to 8 bytes per sample; the pass writes the ones its plan
//!   keeps (`FrameResources::has`), composing its shader for them on first use. A coat
//!   the pass stores dims the emission under it, as it dims the light.
//!
//! The lean G-buffer (pipelines/deferred_msaa_4x_lean.ron) is albedo, normal, material
//! and a `depth32float` depth without stencil: 16 bytes per sample, 20 with emission.
//!
//! With reversed-Z depth is cleared to 0 and tested with `Greater` (near is 1), else
//! cleared to 1 and tested with `Less`. Without `reversed_z` the convention follows the
//! depth format (reversed for float depth, see `common/depth.rs`), as the light
//! passes' does; a `reversed_z` given here must be given to them too.
//! Stencil is cleared to 0. The color targets are not cleared: after the meshes, the
//! samples none drew are filled with what a clear would have left (zeros, the
//! background in `hdr` and `emission`: common/background.rs), which on the H200 costs a
//! fraction of the clear; a pass that lists a target in its inputs too (drawing over it)
//! clears its fresh targets instead. Double-sided materials are drawn without culling and their
//! back faces get the flipped normal; alpha MASK materials discard below the cutoff.
//! Alpha BLEND meshes are not drawn: a sample holds one surface, so the `transparent`
//! pass draws them after lighting (passes/transparent.rs).
//! The material target's alpha records per-sample edge evidence for the `centroid` and
//! `coverage` detectors of [`edge_stencil`](super::edge_stencil).

use serde::Deserialize;

use rgraph_core::file::{Plugin, PluginError, Slots};
use rgraph_core::{PassBuilder, PassKind};

use crate::common::background::FilledTargets;
use crate::common::depth::DepthRule;
use crate::common::gbuffer_layers::{self, LayerSet};
use crate::common::optional_targets::OptionalTargets;
use crate::common::plugin::Shared;
use crate::common::pose_offset;
use crate::common::rgb9e5;
use crate::common::scene_draw::{Masked, SceneDraw, Stages};
use crate::common::textures::{self, Want};
use crate::layers::Layer;
use crate::shaders;
use crate::variant::GatedShader;

pub struct GBuffer(pub(crate) Shared);

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GBufferParams {
    /// Fixes the depth convention; left out, it follows the depth format the compile
    /// picks: reversed-Z for float depth, standard Z for unorm depth.
    #[serde(default)]
    pub reversed_z: Option<bool>,
    /// The HDR target's value where no geometry is drawn (linear RGBA).
    #[serde(default = "opaque_black")]
    pub background: [f64; 4],
}

pub(crate) fn opaque_black() -> [f64; 4] {
    [0.0, 0.0, 0.0, 1.0]
}

impl Plugin for GBuffer {
    const NAME: &'static str = "gbuffer";
    type Params = GBufferParams;

    fn kind(&self, _: &GBufferParams) -> PassKind {
        PassKind::Render
    }

    fn setup(
        &self,
        params: GBufferParams,
        pass: &mut PassBuilder<'_>,
        slots: &mut Slots<'_>,
    ) -> Result<(), PluginError> {
        let depth_rule = DepthRule::new(params.reversed_z);
        let depth_want = Want::new("the G-buffer's depth", textures::DEPTH_ANY);
        let (depth, desc) = textures::output(slots, pass, "depth", depth_want, |pass, h, _| {
            depth_rule.start(pass, h)
        })?;
        let samples = desc.samples;
        if slots.is_output("hdr") && slots.is_output("emission") {
            return Err(PluginError::Invalid(
                "outputs \"hdr\" and \"emission\" both hold the emission: write one \
                 (emission is the lean G-buffer's, hdr the full one's)"
                    .into(),
            ));
        }
        // Filled where no mesh draws rather than cleared first (common/background.rs),
        // unless the pass draws over a target it reads.
        let named: Vec<&str> = CHANNELS
            .iter()
            .map(|c| c.slot)
            .chain(Layer::ALL.map(Layer::slot))
            .collect();
        let mut targets = FilledTargets::new(slots, &named);
        // Each written channel's slot and WGSL type, in attachment order.
        let mut written: Vec<(&'static str, &'static str)> = Vec::with_capacity(named.len());
        let mut pose = None;
        for channel in &CHANNELS {
            if channel.slot != "albedo" && !slots.is_output(channel.slot) {
                continue;
            }
            let clear = match channel.slot {
                "hdr" => params.background,
                "emission" => {
                    let bits = rgb9e5::pack(background_rgb(params.background));
                    [f64::from(bits & 0xffff), f64::from(bits >> 16), 0.0, 0.0]
                }
                _ => [0.0; 4],
            };
            let want = Want::new(channel.what, channel.formats).samples(samples);
            let target = targets.push(slots, pass, channel.slot, want, (channel.wgsl, clear))?;
            written.push((channel.slot, channel.wgsl));
            if channel.slot == pose_offset::SLOT {
                pose = Some(target);
            }
        }
        let layers = gbuffer_layers::push_targets(slots, pass, samples, &mut targets)?;
        written.extend(
            layers
                .iter()
                .map(|&(l, _)| (l.slot(), gbuffer_layers::TARGET_WGSL)),
        );
        let handles = targets.handles().to_vec();
        let optional = (layers, pose);
        let listed = optional.clone();
        // The pass for the layers and pose offset a frame keeps: their channels only, at
        // consecutive locations.
        let make = move |(set, posed): (LayerSet, bool)| {
            let kept = listed.kept_attachments((set, posed), &handles);
            let channels: Vec<(&str, &str)> = written
                .iter()
                .zip(&kept)
                .filter_map(|(&c, &k)| k.then_some(c))
                .collect();
            let targets = targets.only(&kept);
            let outputs = outputs_wgsl(&channels, set.has(Layer::Clearcoat))
                + &targets.wgsl()
                + pose_offset::last_pose_wgsl(posed);
            let source = shaders::GBUFFER.compose_with(samples, &outputs)?;
            let stages = Stages {
                vertex: "vs_main",
                fragment: "fs_opaque",
                masked: Masked::Entry("fs_masked"),
            };
            let fill_background = targets.fill();
            let (targets, shader) = (targets.into_handles(), GatedShader::GBuffer);
            Ok(SceneDraw {
                fill_background,
                last_pose: posed,
                ..SceneDraw::new(
                    "gbuffer",
                    shader,
                    source.source().to_owned(),
                    depth_rule,
                    targets,
                    depth,
                    stages,
                )
            })
        };
        self.0.record_kept(pass, optional, make)
    }
}

/// A color target the pass can write, at the next location when the file lists it.
struct Channel {
    slot: &'static str,
    what: &'static str,
    formats: &'static [rgraph_core::types::TextureFormat],
    /// gbuffer.wgsl's type for it.
    wgsl: &'static str,
}

/// In attachment order. Only `albedo` is required (see the module docs).
const CHANNELS: [Channel; 8] = [
    Channel {
        slot: "albedo",
        what: "the G-buffer's albedo",
        formats: textures::ALBEDO,
        wgsl: "vec4<f32>",
    },
    Channel {
        slot: "normal",
        what: "the G-buffer's normals",
        formats: textures::NORMAL,
        wgsl: "vec4<f32>",
    },
    Channel {
        slot: "material",
        what: "the G-buffer's material",
        formats: textures::MATERIAL,
        wgsl: "vec4<f32>",
    },
    Channel {
        slot: "view_depth",
        what: "the G-buffer's view depth",
        formats: textures::VIEW_DEPTH,
        wgsl: "vec4<f32>",
    },
    Channel {
        slot: "hdr",
        what: "the HDR target",
        formats: textures::HDR,
        wgsl: "vec4<f32>",
    },
    Channel {
        slot: "emission",
        what: "the G-buffer's emission",
        formats: textures::EMISSION,
        wgsl: "vec2<u32>",
    },
    Channel {
        slot: "mesh",
        what: "the G-buffer's mesh index",
        formats: textures::MESH,
        wgsl: "vec2<u32>",
    },
    Channel {
        slot: pose_offset::SLOT,
        what: pose_offset::WHAT,
        formats: textures::POSE_OFFSET,
        wgsl: "vec4<f32>",
    },
];

/// The background's color where the emission channel holds it (RGB9E5 has no alpha).
fn background_rgb(background: [f64; 4]) -> [f32; 3] {
    [background[0], background[1], background[2]].map(|c| c as f32)
}

/// `gbuffer.wgsl`'s fragment output: the `channels` written (slot and WGSL type), at
/// locations counting up from 0 as the pass attaches them, and whether it holds the clear
/// coat (`HOLDS_CLEARCOAT`: the coat then dims the emission).
fn outputs_wgsl(channels: &[(&str, &str)], holds_clearcoat: bool) -> String {
    let fields: String = channels
        .iter()
        .enumerate()
        .map(|(location, (slot, ty))| format!("    @location({location}) {slot}: {ty},\n"))
        .collect();
    let values: Vec<String> = channels
        .iter()
        .map(|(slot, _)| format!("g.{slot}"))
        .collect();
    format!(
        "// Generated: the channels this G-buffer pass writes.\n\
         const HOLDS_CLEARCOAT: bool = {holds_clearcoat};\n\
         struct GBufferOut {{\n{fields}}}\n\n\
         fn gbuffer_out(g: GBuffer) -> GBufferOut {{\n    return GBufferOut({});\n}}\n",
        values.join(", ")
    )
}
