//! `light_prepass_gbuffer` and `light_prepass_material`: the two geometry passes of a light
//! pre-pass (deferred lighting) renderer with MSAA, around the light passes
//! (`light_edge`/`light_nonedge` with `accumulate: light`, passes/light.rs) and the edge
//! pass of deferred MSAA (pipelines/light_prepass_msaa_4x.ron).
//!
//! ```ron
//! (name: "gbuffer (thin)", plugin: "light_prepass_gbuffer",  // params: reversed_z
//!  outputs: {
//!      "normal": "normal",          // rg16float: octahedral shading normal
//!      "material": "material",      // rgba8unorm: gbuffer's layout; roughness and flags are read
//!      "view_depth": "view_depth",  // r32float
//!      "depth": "depth",            // the depth-stencil, written
//!      "clearcoat": "clearcoat",    // optional: the material layers the light passes
//!      "sheen": "sheen",            //   need, as gbuffer writes them
//!  },
//!  optional: ["clearcoat", "sheen"])
//! (name: "material", plugin: "light_prepass_material",
//!  params: (background: (0.0, 0.0, 0.0, 1.0)),               // the default; reversed_z
//!  inputs: { "light": "light", "depth": "depth_edges" },     // the light buffer; depth read-only
//!                                  // and "lobes": the lobes buffer, where the scene has one
//!  outputs: { "hdr": "hdr" })                                 // rgba16float, the same samples
//! ```
//!
//! The thin G-buffer is what lighting needs and no more: normal, roughness (with the
//! flags) and depth, 12 bytes a sample (16 in wgpu's accounting) where deferred shading's
//! G-buffer has 24 (32) with albedo and an HDR target. The light passes accumulate into a
//! multisampled `rgba16float` light buffer (8 bytes a sample), per sample on the edge
//! pixels the edge pass marks and per pixel elsewhere, as deferred MSAA shades: the
//! diffuse light in RGB and the luminance of a dielectric's specular in alpha
//! (light_prepass.wgsl). Then the scene is drawn a second time: the material pass
//! evaluates each mesh's material per sample, where the depth test finds the surface the
//! thin pass drew, reads the light buffer at that sample and writes the lit colour
//! (plus ambient and environment light and emission) into the multisampled HDR target,
//! which a resolve averages as deferred MSAA's is.
//!
//! What it costs and saves against deferred MSAA: a second pass over the geometry
//! (vertices again, and the material's textures sampled per sample), against a G-buffer
//! half as wide to write and read back in every light pass; the light buffer replaces
//! nothing (deferred MSAA accumulates into its HDR target, which the material pass still
//! writes). Its specular differs: one channel holds a dielectric's (F0 = 0.04), coloured
//! like the diffuse light. A dielectric under white light (or lights of one colour)
//! comes out as deferred shading computes it; a metal's coloured specular is the
//! dielectric's scaled by a Fresnel ratio taken at n.v rather than at each light's v.h,
//! and under lights of different colours specular takes the mix of their colours.
//!
//! The material layers: KHR_materials_ior and _specular need nothing of the light
//! passes (the material pass scales the specular's Fresnel to the layer's F0 and weight,
//! as for metals, and leaves out the weight's own (1 - F90) share of the diffuse at each
//! light's grazing angle). A clear coat and a sheen are lobes of their own, with their own
//! roughness (and the coat its own normal): for a scene with them (`layer_lobes`) the
//! thin G-buffer stores the `clearcoat` and `sheen` targets (gbuffer.rs's layers, 2 or 8
//! and 4 bytes a sample; the pass writes those its plan keeps), the light passes add the
//! coat's lobe, the sheen's and the sheen's share of the base into a second
//! `rgba16float` buffer, `lobes` (8 bytes a sample; light_prepass.wgsl), and the material
//! pass layers them over the base as brdf.wgsl does, coloured by the diffuse light's
//! chroma; the base under a sheen is dimmed by the mean of the sheen's E over the lights,
//! weighed by their diffuse light (exact for one light).

use serde::Deserialize;

use rgraph_core::file::{Plugin, PluginError, Slots};
use rgraph_core::{AspectAccess, PassBuilder, PassKind, TextureHandle};

use super::gbuffer::opaque_black;
use crate::common::background::FilledTargets;
use crate::common::depth::DepthRule;
use crate::common::gbuffer_layers::{self, LayerSet};
use crate::common::optional_targets::OptionalTargets;
use crate::common::plugin::Shared;
use crate::common::scene_draw::{Masked, SceneDraw, Stages};
use crate::common::textures::{self, Want};
use crate::layers::Layer;
use crate::shaders;
use crate::variant::GatedShader;

pub struct LightPrepassGBuffer(pub(crate) Shared);
pub struct LightPrepassMaterial(pub(crate) Shared);

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LightPrepassGBufferParams {
    /// Fixes the depth convention; left out, it follows the depth format the compile
    /// picks: reversed-Z for float depth, standard Z for unorm depth.
    #[serde(default)]
    pub reversed_z: Option<bool>,
}

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LightPrepassMaterialParams {
    /// As for the thin G-buffer pass, which must say the same.
    #[serde(default)]
    pub reversed_z: Option<bool>,
    /// The HDR target's value where no geometry is drawn (linear RGBA).
    #[serde(default = "opaque_black")]
    pub background: [f64; 4],
}

/// A geometry pass: the scene's opaque meshes at `samples` per pixel with forward.wgsl's
/// vertex stages (the module is forward.wgsl's, and its gates), alpha masks through its
/// `MASKED`.
fn geometry_draw(
    label: &'static str,
    (vertex, fragment): (&'static str, &'static str),
    samples: u32,
    depth_rule: DepthRule,
    (targets, generated): (FilledTargets, String),
    depth: TextureHandle,
) -> Result<SceneDraw, PluginError> {
    let generated = generated + &targets.wgsl();
    let source = shaders::LIGHT_PREPASS_GEOMETRY.compose_with(samples, &generated)?;
    let stages = Stages {
        vertex,
        fragment,
        masked: Masked::Constant,
    };
    Ok(SceneDraw {
        fill_background: targets.fill(),
        ..SceneDraw::new(
            label,
            GatedShader::Forward,
            source.source().to_owned(),
            depth_rule,
            targets.into_handles(),
            depth,
            stages,
        )
    })
}

/// light_prepass_material.wgsl's generated block: the thin G-buffer's `ThinGBuffer` and
/// `thin_gbuffer`, its core targets and then the material `layers` the thin pass writes
/// (gbuffer_layers.wgsl's encodings), and `LOBES` and `load_lobes`, the material pass's
/// lobes buffer (group 2, binding 1) where it reads one.
fn generated_wgsl(layers: &[Layer], lobes: bool) -> String {
    let fields: String = layers
        .iter()
        .enumerate()
        .map(|(i, layer)| format!("    @location({}) {}: vec4<f32>,\n", 3 + i, layer.slot()))
        .collect();
    let values: String = layers
        .iter()
        .map(|layer| format!(", encode_{}(layers)", layer.slot()))
        .collect();
    let lobes = match lobes {
        true => {
            "const LOBES: bool = true;\n\
                 @group(2) @binding(1) var lobes_tex: GTexF;\n\
                 fn load_lobes(pixel: vec2<i32>, s: u32) -> vec4<f32> {\n\
                 \x20   return textureLoad(lobes_tex, pixel, s);\n}\n"
        }
        false => {
            "const LOBES: bool = false;\n\
                  fn load_lobes(pixel: vec2<i32>, s: u32) -> vec4<f32> {\n\
                  \x20   return vec4<f32>(0.0);\n}\n"
        }
    };
    format!(
        "// Generated: the thin G-buffer's targets and the lobes buffer (light_prepass.rs).\n\
         struct ThinGBuffer {{\n\
         \x20   @location(0) normal: vec4<f32>,\n\
         \x20   @location(1) material: vec4<f32>,\n\
         \x20   @location(2) view_depth: vec4<f32>,\n{fields}}}\n\n\
         fn thin_gbuffer(normal: vec4<f32>, material: vec4<f32>, view_depth: vec4<f32>, \
         layers: Layers) -> ThinGBuffer {{\n\
         \x20   return ThinGBuffer(normal, material, view_depth{values});\n}}\n\n{lobes}"
    )
}

impl Plugin for LightPrepassGBuffer {
    const NAME: &'static str = "light_prepass_gbuffer";
    type Params = LightPrepassGBufferParams;

    fn kind(&self, _: &LightPrepassGBufferParams) -> PassKind {
        PassKind::Render
    }

    fn setup(
        &self,
        params: LightPrepassGBufferParams,
        pass: &mut PassBuilder<'_>,
        slots: &mut Slots<'_>,
    ) -> Result<(), PluginError> {
        let depth_rule = DepthRule::new(params.reversed_z);
        let want = Want::new("the thin G-buffer's depth-stencil", textures::DEPTH_STENCIL);
        let (depth, desc) = textures::output(slots, pass, "depth", want, |pass, h, _| {
            depth_rule.start(pass, h)
        })?;
        let samples = desc.samples;
        // Filled where no mesh draws rather than cleared first (common/background.rs),
        // unless the pass draws over a target it reads.
        let named: Vec<&str> = ["normal", "material", "view_depth"]
            .into_iter()
            .chain(Layer::ALL.map(Layer::slot))
            .collect();
        let mut targets = FilledTargets::new(slots, &named);
        for (slot, what, formats) in [
            ("normal", "the thin G-buffer's normals", textures::NORMAL),
            (
                "material",
                "the thin G-buffer's material",
                textures::MATERIAL,
            ),
            (
                "view_depth",
                "the thin G-buffer's view depth",
                textures::VIEW_DEPTH,
            ),
        ] {
            let want = Want::new(what, formats).samples(samples);
            targets.push(slots, pass, slot, want, ("vec4<f32>", [0.0; 4]))?;
        }
        let layers = gbuffer_layers::push_targets(slots, pass, samples, &mut targets)?;
        let handles = targets.handles().to_vec();
        let listed = layers.clone();
        // The pass for the layers a frame keeps, at consecutive locations after the rest.
        let make = move |set: LayerSet| {
            let kept = listed.kept_attachments(set, &handles);
            let written: Vec<Layer> = listed
                .iter()
                .map(|&(layer, _)| layer)
                .filter(|&layer| set.has(layer))
                .collect();
            let generated = generated_wgsl(&written, false);
            let stages = ("vs_pixel", "fs_thin_gbuffer");
            let targets = (targets.only(&kept), generated);
            geometry_draw(
                "light_prepass_gbuffer",
                stages,
                samples,
                depth_rule,
                targets,
                depth,
            )
        };
        self.0.record_kept(pass, layers, make)
    }
}

impl Plugin for LightPrepassMaterial {
    const NAME: &'static str = "light_prepass_material";
    type Params = LightPrepassMaterialParams;

    fn kind(&self, _: &LightPrepassMaterialParams) -> PassKind {
        PassKind::Render
    }

    fn setup(
        &self,
        params: LightPrepassMaterialParams,
        pass: &mut PassBuilder<'_>,
        slots: &mut Slots<'_>,
    ) -> Result<(), PluginError> {
        let want = Want::new("the thin G-buffer's depth-stencil", textures::DEPTH_STENCIL);
        let (depth, desc) = textures::input(slots, pass, "depth", want)?;
        pass.depth_stencil(depth, AspectAccess::ReadOnly, AspectAccess::ReadOnly);
        let samples = desc.samples;
        let want = Want::new("the light buffer", textures::HDR).samples(samples);
        let (light, _) = textures::sampled(slots, pass, "light", want, 0)?;
        let mut read = vec![light];
        if slots.kind("lobes").is_some() {
            let want = Want::new("the lobes buffer", textures::HDR).samples(samples);
            read.push(textures::sampled(slots, pass, "lobes", want, 1)?.0);
        }
        let want = Want::new("the HDR target", textures::HDR).samples(samples);
        // Filled with the background where no mesh draws, as forward's is.
        let mut targets = FilledTargets::new(slots, &["hdr"]);
        targets.push(slots, pass, "hdr", want, ("vec4<f32>", params.background))?;
        let stages = ("vs_sample", "fs_apply_material");
        let (label, rule) = ("light_prepass_material", DepthRule::new(params.reversed_z));
        let generated = generated_wgsl(&[], read.len() > 1);
        let draw = SceneDraw {
            redraw: Some(read),
            ..geometry_draw(label, stages, samples, rule, (targets, generated), depth)?
        };
        self.0.record(pass, draw);
        Ok(())
    }
}
