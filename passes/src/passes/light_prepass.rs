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
//!  })
//! (name: "material", plugin: "light_prepass_material",
//!  params: (background: (0.0, 0.0, 0.0, 1.0)),               // the default; reversed_z
//!  inputs: { "light": "light", "depth": "depth_edges" },     // the light buffer; depth read-only
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

use serde::Deserialize;

use rgraph_core::file::{Plugin, PluginError, Slots};
use rgraph_core::{AspectAccess, PassBuilder, PassKind, TextureHandle};

use super::gbuffer::opaque_black;
use crate::common::background::FilledTargets;
use crate::common::depth::DepthRule;
use crate::common::plugin::Shared;
use crate::common::scene_draw::{Masked, SceneDraw, Stages};
use crate::common::textures::{self, Want};
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
    targets: FilledTargets,
    depth: TextureHandle,
) -> Result<SceneDraw, PluginError> {
    let source = shaders::LIGHT_PREPASS_GEOMETRY.compose_with(samples, &targets.wgsl())?;
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
        let mut targets = FilledTargets::new(slots, &["normal", "material", "view_depth"]);
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
        let stages = ("vs_pixel", "fs_thin_gbuffer");
        let label = "light_prepass_gbuffer";
        let draw = geometry_draw(label, stages, samples, depth_rule, targets, depth)?;
        self.0.record(pass, draw);
        Ok(())
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
        let want = Want::new("the HDR target", textures::HDR).samples(samples);
        // Filled with the background where no mesh draws, as forward's is.
        let mut targets = FilledTargets::new(slots, &["hdr"]);
        targets.push(slots, pass, "hdr", want, ("vec4<f32>", params.background))?;
        let stages = ("vs_sample", "fs_apply_material");
        let (label, rule) = ("light_prepass_material", DepthRule::new(params.reversed_z));
        let draw = SceneDraw {
            redraw: Some(vec![light]),
            ..geometry_draw(label, stages, samples, rule, targets, depth)?
        };
        self.0.record(pass, draw);
        Ok(())
    }
}
