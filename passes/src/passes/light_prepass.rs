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

use graph_core::file::{Plugin, PluginError, Slots};
use graph_core::{AspectAccess, PassBuilder, PassKind, TextureHandle};

use super::gbuffer::opaque_black;
use crate::common::background::FilledTargets;
use crate::common::depth::DepthRule;
use crate::common::plugin::{Recording, Shared};
use crate::common::textures::{self, Input, Want};
use crate::shaders;

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

/// A light pre-pass geometry pass as set up: what its `gpu` module records.
#[cfg_attr(not(feature = "gpu"), allow(dead_code))]
pub(crate) struct GeometryDraw {
    pub source: String,
    pub depth_rule: DepthRule,
    /// Color attachments in location order.
    pub targets: Vec<TextureHandle>,
    pub depth: TextureHandle,
    /// The material pass's light buffer; `None` for the thin G-buffer pass.
    pub light: Option<Input>,
    /// The targets begin undrawn and are filled where no mesh draws (common/background.rs).
    pub fill_background: bool,
}

impl Recording for GeometryDraw {
    #[cfg(feature = "gpu")]
    fn record(self, scenes: std::sync::Arc<crate::gpu_scene::SceneCache>) -> graph_core::Record {
        graph_core::Record::Render(gpu::record(self, scenes))
    }
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
        let draw = GeometryDraw {
            source: shaders::LIGHT_PREPASS_GEOMETRY
                .compose_with(samples, &targets.wgsl())?
                .source()
                .to_owned(),
            depth_rule,
            fill_background: targets.fill(),
            targets: targets.into_handles(),
            depth,
            light: None,
        };
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
        let draw = GeometryDraw {
            source: shaders::LIGHT_PREPASS_GEOMETRY
                .compose_with(samples, &targets.wgsl())?
                .source()
                .to_owned(),
            depth_rule: DepthRule::new(params.reversed_z),
            fill_background: targets.fill(),
            targets: targets.into_handles(),
            depth,
            light: Some(light),
        };
        self.0.record(pass, draw);
        Ok(())
    }
}

#[cfg(feature = "gpu")]
mod gpu {
    //! Recording the two geometry passes: the scene's opaque meshes with forward.wgsl's
    //! vertex stages, into the thin G-buffer per pixel, or over its depth per sample with
    //! the light buffer as group 2.

    use std::sync::Arc;

    use graph_core::gpu::RenderContext;

    use super::GeometryDraw;
    use crate::common::gpu::scene_draw::{self, Redraw, SceneDraw, Stages};
    use crate::gpu_scene::{Layer, SceneCache};
    use crate::variant::GatedShader;

    pub(super) fn record(
        draw: GeometryDraw,
        scenes: Arc<SceneCache>,
    ) -> Box<dyn FnMut(&mut RenderContext<'_, '_>)> {
        let (label, vertex, fragment) = match draw.light {
            None => ("light_prepass_gbuffer", "vs_pixel", "fs_thin_gbuffer"),
            Some(_) => ("light_prepass_material", "vs_sample", "fs_apply_material"),
        };
        let redraw = draw.light.map(|light| Redraw {
            inputs: vec![light],
        });
        let scene_draw = SceneDraw {
            label,
            // forward.wgsl's gates: the module is forward.wgsl's and its entry points.
            shader: GatedShader::Forward,
            source: draw.source,
            depth_rule: draw.depth_rule,
            targets: draw.targets,
            depth: draw.depth,
            layer: Layer::Opaque,
            begin_blended: None,
            fill_background: draw.fill_background,
            stages: Box::new(move |material| Stages {
                vertex,
                fragment,
                constants: vec![("MASKED", f64::from(u8::from(material.masked)))],
            }),
        };
        scene_draw::record_with(scene_draw, redraw, scenes)
    }
}
