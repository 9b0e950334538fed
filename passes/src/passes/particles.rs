//! `particles` and `composite_particles`: seed 001's particles, drawn after the opaque
//! scene is lit, at full resolution or off screen at a fraction of it and composited back.
//!
//! ```ron
//! // Full resolution (the baseline), or the second, full-resolution pass of mixed
//! // resolution (with "stencil": only where the composite left the stencil unmarked):
//! (name: "particles", plugin: "particles",
//!  params: (softness: 4.0, pad: 0),   // the defaults; reversed_z optional
//!  inputs: { "depth": "depth", "hdr": "resolved_hdr" },   // + "stencil": "particle_stencil"
//!  outputs: { "hdr": "resolved_particles" }),
//! // Off screen: into targets cleared by the pass, tested against a downsampled depth.
//! (name: "particles (low res)", plugin: "particles",
//!  inputs: { "depth": "particle_depth" },      // r32float view depth (depth_downsample)
//!  outputs: { "color": "particle_color", "additive": "particle_additive" }),
//! (name: "composite particles", plugin: "composite_particles",
//!  inputs: { "color": "particle_color", "additive": "particle_additive",
//!            "resolved": "resolved_hdr" },      // + "edges": "particle_edges" (mixed)
//!  outputs: { "resolved": "resolved" }),        // + "stencil": "particle_stencil" (mixed)
//! // In compute (no ROPs): off screen only, and the composite writes a new image, as a
//! // compute pass cannot read and write one rgba16float texture in one dispatch.
//! (name: "particles (compute)", plugin: "particles", params: (stage: compute),
//!  inputs: { "depth": "particle_depth" },
//!  outputs: { "color": "particle_color", "additive": "particle_additive" }),
//! (name: "composite particles", plugin: "composite_particles", params: (stage: compute),
//!  inputs: { "color": "particle_color", "additive": "particle_additive",
//!            "hdr": "resolved_hdr" },
//!  outputs: { "resolved": "composited" }),   // rgba16float, the output's size
//! ```
//!
//! **The particle pass** draws the frame's particles (`FrameInputs::emitters`: the
//! scene's, or wherever an engine's simulation took them; gpu_scene/particles.rs) as
//! camera-facing billboards in one instanced draw per kind:
//! the blended ones (smoke) back to front, then the emissive ones (fire). Each fragment's
//! opacity is the particle's alpha times a procedural soft texture times the seed's
//! soft-particle fade `zFade = saturate(softness * (scene depth - particle depth))` in view
//! depth (world units): the depth test happens in the fragment shader against `depth`,
//! so a particle behind a surface is hidden and one crossing it fades out over the last
//! `1 / softness` units. `depth` is the multisampled depth-stencil of the opaque passes
//! (sample 0 of the fragment's pixel, turned into view depth with the camera of its
//! depth convention) or a single-sampled `r32float` view depth at the targets' size
//! (`depth_downsample`). **Lighting**: ambient and emission only. A blended particle's
//! colour is its albedo times the scene's ambient radiance; an emissive particle adds
//! its colour times its opacity. Per-light shading would multiply the cost the seed
//! wants to cut by the lights reaching each fragment.
//!
//! Blending. With an `hdr` output (the single-sampled HDR image, modified in place) a
//! blended particle is blended over it (`src * a + dst * (1 - a)`) and an emissive one
//! added. With `color` and `additive` outputs (off screen), as the seed: `color` is
//! cleared to (0, 0, 0, 1) and accumulates colour by conventional alpha blending and, in
//! alpha, the product of `1 - a` (the transmittance: the seed's separate alpha blend,
//! source factor zero, destination `1 - a`); `additive` is cleared to black and sums the
//! emissive particles. The two targets are the two attachments of one pass, each draw
//! writing one of them. Either way the emissive particles come after every blended one,
//! so full and off-screen resolution agree: `hdr * T + C + A`.
//!
//! `pad` adds that many multiply-adds to every fragment without changing it, to measure
//! time against shader cost (the seed's Table 23-2).
//!
//! **In compute** (`stage: compute`, particles_raster.wgsl): the same particles, opacities
//! and blending off screen, a workgroup per 16 x 16 pixels of the targets blending the
//! particles that may cover its tile in their order, in registers, and storing `color`
//! and `additive` once (storage writes). Against a single-sampled view depth only (the
//! full-resolution pass's depth test and stencil are the fragment pass's). The fragment
//! pass pays the ROPs for every blended fragment, which on a chip with few of them is
//! most of its time. Every tile walks every particle, a chunk of 256 at a time: fine for
//! the thousands of a smoke column, linear in the count beyond.
//!
//! **The composite** is a full-screen draw onto the output-sized HDR image (`resolved`,
//! modified in place) that upsamples `color` and `additive` bilinearly and blends
//! `resolved * T + C + A` (the alpha, a background's transmittance, times T). With
//! `stage: compute` it computes the same per pixel from the image `hdr` and stores every
//! pixel of a new one, `resolved`. With `edges` (particle_edges' Sobel mask, at the off-screen
//! size) and `stencil` (a `stencil8` texture of the output's size, cleared here) it is
//! the mixed-resolution composite: it discards wherever any of a pixel's four bilinear
//! texels is an edge, and marks the stencil (0x80) wherever it composited, so a second
//! `particles` pass with that `stencil` draws at full resolution in the edge areas only.

use serde::Deserialize;

use rgraph_core::file::{Plugin, PluginError, Slots};
use rgraph_core::shader::Stage;
use rgraph_core::types::TextureFormat;
use rgraph_core::{Aspect, AspectAccess, ColorLoad, PassBuilder, PassKind, TextureDesc};

use super::transparent::UNDER_TRANSMITTANCE;
use crate::common::depth::DepthRule;
use crate::common::fullscreen::Fullscreen;
use crate::common::fullscreen_compute::FullscreenCompute;
use crate::common::plugin::Shared;
use crate::common::textures::{self, Input, Texels, Want};
use crate::shaders;

pub struct Particles(pub(crate) Shared);
pub struct CompositeParticles(pub(crate) Shared);

/// The most `pad` multiply-adds per fragment.
pub const MAX_PAD: u32 = 4096;

/// Whether a particle plugin draws (fragment stage, the seed's) or computes.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ParticleStage {
    #[default]
    Fragment,
    Compute,
}

impl ParticleStage {
    fn kind(self) -> PassKind {
        match self {
            ParticleStage::Fragment => PassKind::Render,
            ParticleStage::Compute => PassKind::Compute,
        }
    }
}

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ParticlesParams {
    /// The soft-particle scale, per world unit: a particle fades out over the last
    /// `1 / softness` units in front of a surface. Finite and positive (default 4).
    #[serde(default = "default_softness")]
    pub softness: f32,
    /// Extra multiply-adds per fragment, at most [`MAX_PAD`] (default 0).
    #[serde(default)]
    pub pad: u32,
    /// Fixes the depth convention of a depth-stencil `depth`; left out, it follows the
    /// depth format the compile picks, as the opaque passes' does.
    #[serde(default)]
    pub reversed_z: Option<bool>,
    #[serde(default)]
    pub stage: ParticleStage,
}

fn default_softness() -> f32 {
    4.0
}

#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CompositeParticlesParams {
    #[serde(default)]
    pub stage: ParticleStage,
}

/// The compute raster's tile side, in pixels of the targets.
const TILE: u32 = 16;

/// The formats `depth` may have: a depth-stencil, or a view depth.
const SCENE_DEPTH: &[TextureFormat] = &[
    TextureFormat::Depth24PlusStencil8,
    TextureFormat::Depth32FloatStencil8,
    TextureFormat::R32Float,
];
/// The stencil the mixed-resolution composite marks.
pub(crate) const STENCIL: &[TextureFormat] = &[TextureFormat::Stencil8];
/// particle_edges' mask.
pub(crate) const EDGES: &[TextureFormat] = &[TextureFormat::R8Unorm];

/// A slot error on `slot`.
pub(crate) fn slot_error(slots: &Slots<'_>, slot: &str, why: String) -> PluginError {
    PluginError::Slot {
        slot: slot.to_owned(),
        resource: slots.resource(slot).unwrap_or(slot).to_owned(),
        why,
    }
}

/// Fails unless `desc` (slot `slot`'s) has the size of `other` (slot `other_slot`'s),
/// which the pass reads texel for texel with it.
pub(crate) fn same_size(
    slots: &Slots<'_>,
    (slot, desc): (&str, &TextureDesc),
    (other_slot, other): (&str, &TextureDesc),
) -> Result<(), PluginError> {
    if desc.size == other.size {
        return Ok(());
    }
    let why = format!(
        "is {:?}, but \"{}\" (slot \"{other_slot}\") is {:?}: the pass reads them texel for texel",
        desc.size,
        slots.resource(other_slot).unwrap_or(other_slot),
        other.size
    );
    Err(slot_error(slots, slot, why))
}

impl ParticlesParams {
    fn check(&self) -> Result<(), PluginError> {
        if !(self.softness.is_finite() && self.softness > 0.0) {
            return Err(PluginError::Invalid(format!(
                "softness {} must be finite and positive (per world unit: a particle fades \
                 out over the last 1 / softness units in front of a surface)",
                self.softness
            )));
        }
        if self.pad > MAX_PAD {
            return Err(PluginError::Invalid(format!(
                "pad {} is more than {MAX_PAD} multiply-adds per fragment",
                self.pad
            )));
        }
        Ok(())
    }
}

impl Plugin for Particles {
    const NAME: &'static str = "particles";
    type Params = ParticlesParams;

    fn kind(&self, params: &ParticlesParams) -> PassKind {
        params.stage.kind()
    }

    fn setup(
        &self,
        params: ParticlesParams,
        pass: &mut PassBuilder<'_>,
        slots: &mut Slots<'_>,
    ) -> Result<(), PluginError> {
        params.check()?;
        if params.stage == ParticleStage::Compute {
            return self.setup_compute(params, pass, slots);
        }
        let want = Want::new(
            "the scene depth (a depth-stencil or an r32float view depth)",
            SCENE_DEPTH,
        );
        let (depth, depth_desc) = textures::input(slots, pass, "depth", want)?;
        let view_depth = depth_desc.format == TextureFormat::R32Float;
        let (input, depth_rule, samples) = if view_depth {
            if depth_desc.samples != 1 {
                let why = "is a multisampled view depth: the particle pass reads one value per \
                           pixel (depth_downsample makes it)";
                return Err(slot_error(slots, "depth", why.to_owned()));
            }
            pass.sampled(depth);
            (Input::color(0, depth), None, 1)
        } else {
            pass.sampled_aspect(depth, Aspect::DepthOnly);
            let input = Input {
                binding: 0,
                texture: depth,
                aspect: Aspect::DepthOnly,
                texels: Texels::Depth,
            };
            (
                input,
                Some(DepthRule::new(params.reversed_z)),
                depth_desc.samples,
            )
        };
        let (targets, target_desc) = if slots.is_output("hdr") {
            let want = Want::new("the resolved HDR image", textures::HDR).samples(1);
            let mut modifies = true;
            let (hdr, desc) = textures::output(slots, pass, "hdr", want, |pass, h, m| {
                modifies = m;
                pass.color_output(h, ColorLoad::Load)
            })?;
            textures::must_modify(slots, "hdr", modifies, "blends particles onto it")?;
            (vec![hdr], desc)
        } else {
            let want = Want::new("the off-screen particle colour", textures::HDR).samples(1);
            // Transmittance 1 where no particle is drawn: the composite leaves those pixels.
            let clear = [0.0, 0.0, 0.0, 1.0];
            let (color, desc) = textures::color_output(slots, pass, "color", want, clear)?;
            let want = Want::new("the off-screen emissive particles", textures::HDR).samples(1);
            let (additive, additive_desc) =
                textures::color_output(slots, pass, "additive", want, [0.0; 4])?;
            same_size(slots, ("additive", &additive_desc), ("color", &desc))?;
            (vec![color, additive], desc)
        };
        let target_slot = if targets.len() == 1 { "hdr" } else { "color" };
        if view_depth {
            same_size(slots, ("depth", &depth_desc), (target_slot, &target_desc))?;
        } else if depth_desc.size != target_desc.size {
            let why = format!(
                "is {:?}, but the particles are drawn at {:?}: a full-resolution pass reads \
                 the depth-stencil of its own size; off screen, read depth_downsample's \
                 view depth",
                depth_desc.size, target_desc.size
            );
            return Err(slot_error(slots, "depth", why));
        }
        let stencil = match slots.kind("stencil") {
            None => None,
            Some(_) => {
                let want = Want::new("the mixed-resolution stencil", STENCIL).samples(1);
                let (stencil, desc) = textures::input(slots, pass, "stencil", want)?;
                same_size(slots, ("stencil", &desc), (target_slot, &target_desc))?;
                pass.depth_stencil(stencil, AspectAccess::ReadOnly, AspectAccess::ReadOnly);
                Some(stencil)
            }
        };
        let generated = match view_depth {
            true => VIEW_DEPTH_BINDING.to_owned(),
            false => format!(
                "{}\n@group(1) @binding(0) var scene_depth: GTexD;\n\
                 fn scene_view_depth(pixel: vec2<i32>) -> f32 {{\n    \
                 return view_depth_of(textureLoad(scene_depth, pixel, 0));\n}}\n",
                shaders::PARTICLE_DEPTH
            ),
        };
        let draw = ParticleDraw {
            source: shaders::PARTICLES
                .compose_with(samples, &generated)?
                .source()
                .to_owned(),
            depth: input,
            depth_rule,
            targets,
            stencil,
            constants: vec![
                ("SOFTNESS", f64::from(params.softness)),
                ("PAD", f64::from(params.pad)),
            ],
        };
        self.0.record(pass, draw);
        Ok(())
    }
}

/// particles.wgsl's scene depth from an r32float view depth at group 1 binding 0.
const VIEW_DEPTH_BINDING: &str = "@group(1) @binding(0) var scene_depth: texture_2d<f32>;\n\
     fn scene_view_depth(pixel: vec2<i32>) -> f32 {\n    \
     return textureLoad(scene_depth, pixel, 0).r;\n}\n";

impl Particles {
    /// `stage: compute`: the off-screen targets stored by particles_raster.wgsl.
    fn setup_compute(
        &self,
        params: ParticlesParams,
        pass: &mut PassBuilder<'_>,
        slots: &mut Slots<'_>,
    ) -> Result<(), PluginError> {
        for slot in ["hdr", "stencil"] {
            if slots.kind(slot).is_some() {
                let why = "is for the fragment stage: in compute the particles are drawn off \
                           screen into \"color\" and \"additive\"";
                return Err(slot_error(slots, slot, why.to_owned()));
            }
        }
        let want = Want::new(
            "the scene's view depth (depth_downsample)",
            textures::VIEW_DEPTH,
        )
        .samples(1);
        let (depth, depth_desc) = textures::sampled(slots, pass, "depth", want, 0)?;
        let mut targets = Vec::new();
        for (slot, what, binding) in [
            ("color", "the off-screen particle colour", 1),
            ("additive", "the off-screen emissive particles", 2),
        ] {
            let want = Want::new(what, textures::HDR).samples(1);
            let (target, desc) =
                textures::output(slots, pass, slot, want, |pass, h, _| pass.storage_write(h))?;
            same_size(slots, ("depth", &depth_desc), (slot, &desc))?;
            targets.push(Input {
                binding,
                texture: target,
                aspect: Aspect::All,
                texels: Texels::Store,
            });
        }
        let generated = format!("const TILE: u32 = {TILE}u;\n{VIEW_DEPTH_BINDING}");
        let source = shaders::PARTICLES_RASTER.compose_with(1, &generated)?;
        let Some(entry) = source.entry("cs_particles", Stage::Compute) else {
            return Err(PluginError::Invalid(
                "particles_raster.wgsl has no entry point cs_particles".into(),
            ));
        };
        pass.workgroup(entry.workgroup());
        let dispatch = ParticleDispatch {
            source: source.source().to_owned(),
            inputs: [depth, targets[0], targets[1]],
            constants: vec![
                ("SOFTNESS", f64::from(params.softness)),
                ("PAD", f64::from(params.pad)),
            ],
        };
        self.0.record(pass, dispatch);
        Ok(())
    }
}

impl Plugin for CompositeParticles {
    const NAME: &'static str = "composite_particles";
    type Params = CompositeParticlesParams;

    fn kind(&self, params: &CompositeParticlesParams) -> PassKind {
        params.stage.kind()
    }

    fn setup(
        &self,
        params: CompositeParticlesParams,
        pass: &mut PassBuilder<'_>,
        slots: &mut Slots<'_>,
    ) -> Result<(), PluginError> {
        if params.stage == ParticleStage::Compute {
            return self.setup_compute(pass, slots);
        }
        let want = Want::new("the off-screen particle colour", textures::HDR).samples(1);
        let (color, color_desc) = textures::sampled(slots, pass, "color", want, 0)?;
        let want = Want::new("the off-screen emissive particles", textures::HDR).samples(1);
        let (additive, additive_desc) = textures::sampled(slots, pass, "additive", want, 1)?;
        same_size(slots, ("additive", &additive_desc), ("color", &color_desc))?;
        let want = Want::new("the resolved HDR image", textures::HDR).samples(1);
        let mut modifies = true;
        let (target, desc) = textures::output(slots, pass, "resolved", want, |pass, h, m| {
            modifies = m;
            pass.color_output(h, ColorLoad::Load)
        })?;
        textures::must_modify(slots, "resolved", modifies, "blends particles onto it")?;
        if desc.size != rgraph_core::Size::Relative(1.0) {
            let why = format!(
                "is {:?}: the composite upsamples onto the output size (Relative(1.0)), \
                 whose pixels the camera's viewport counts",
                desc.size
            );
            return Err(slot_error(slots, "resolved", why));
        }
        let mut inputs = vec![color, additive];
        let (entry, stencil_mark) = match (slots.kind("edges"), slots.is_output("stencil")) {
            (None, false) => ("fs_composite_particles", None),
            (Some(_), true) => {
                let want = Want::new("the particle edges", EDGES).samples(1);
                let (edges, edges_desc) = textures::sampled(slots, pass, "edges", want, 2)?;
                same_size(slots, ("edges", &edges_desc), ("color", &color_desc))?;
                inputs.push(edges);
                let want = Want::new("the mixed-resolution stencil", STENCIL).samples(1);
                let (stencil, stencil_desc) =
                    textures::output(slots, pass, "stencil", want, |pass, h, _| {
                        pass.depth_stencil(h, AspectAccess::ReadOnly, AspectAccess::Clear(0))
                    })?;
                same_size(slots, ("stencil", &stencil_desc), ("resolved", &desc))?;
                ("fs_composite_particles_masked", Some(stencil))
            }
            (edges, _) => {
                let (slot, why) = match edges {
                    Some(_) => ("edges", "is given without a \"stencil\" output"),
                    None => ("stencil", "is given without an \"edges\" input"),
                };
                let why = format!(
                    "{why}: the mixed-resolution composite needs both, to mark in the \
                     stencil where it composited, away from the edges"
                );
                return Err(slot_error(slots, slot, why));
            }
        };
        let source = shaders::PARTICLE_COMPOSITE.compose(1)?.source().to_owned();
        let draw = Fullscreen {
            reads_scene: true,
            stencil_mark,
            blend: Some(UNDER_TRANSMITTANCE),
            ..Fullscreen::new("composite particles", source, entry, inputs, Some(target))
        };
        self.0.record(pass, draw);
        Ok(())
    }
}

impl CompositeParticles {
    /// `stage: compute`: `resolved` stored from the image `hdr` and the targets.
    fn setup_compute(
        &self,
        pass: &mut PassBuilder<'_>,
        slots: &mut Slots<'_>,
    ) -> Result<(), PluginError> {
        for slot in ["edges", "stencil"] {
            if slots.kind(slot).is_some() {
                let why = "is for the fragment stage's mixed-resolution composite";
                return Err(slot_error(slots, slot, why.to_owned()));
            }
        }
        let want = Want::new("the off-screen particle colour", textures::HDR).samples(1);
        let (color, color_desc) = textures::sampled(slots, pass, "color", want, 0)?;
        let want = Want::new("the off-screen emissive particles", textures::HDR).samples(1);
        let (additive, additive_desc) = textures::sampled(slots, pass, "additive", want, 1)?;
        same_size(slots, ("additive", &additive_desc), ("color", &color_desc))?;
        let want = Want::new("the resolved HDR image", textures::HDR).samples(1);
        let (under, under_desc) = textures::sampled(slots, pass, "hdr", want, 3)?;
        let want = Want::new("the composited HDR image, a storage texture", textures::HDR);
        let mut modifies = false;
        let (target, desc) =
            textures::output(slots, pass, "resolved", want.samples(1), |pass, h, m| {
                modifies = m;
                pass.storage_write(h)
            })?;
        if modifies {
            let why = "is read and written: in compute the composite stores a new image from \
                       \"hdr\" (name another texture)";
            return Err(slot_error(slots, "resolved", why.to_owned()));
        }
        same_size(slots, ("hdr", &under_desc), ("resolved", &desc))?;
        let stored = Input {
            binding: 4,
            texture: target,
            aspect: Aspect::All,
            texels: Texels::Store,
        };
        let dispatch = FullscreenCompute {
            label: "composite particles",
            source: shaders::PARTICLE_COMPOSITE.compose(1)?.source().to_owned(),
            entry: "cs_composite_particles",
            constants: Vec::new(),
            inputs: vec![color, additive, under, stored],
            reads_scene: true,
            target,
            depth: None,
        };
        self.0.record(pass, dispatch);
        Ok(())
    }
}

/// The particle pass in compute as set up: its scene depth and targets (group 1,
/// bindings 0, 1 and 2).
#[cfg_attr(not(feature = "gpu"), allow(dead_code))]
struct ParticleDispatch {
    source: String,
    inputs: [Input; 3],
    constants: Vec<(&'static str, f64)>,
}

/// The particle pass as set up: see the module documentation.
#[cfg_attr(not(feature = "gpu"), allow(dead_code))]
struct ParticleDraw {
    source: String,
    /// Group 1 binding 0.
    depth: Input,
    /// `Some` for a depth-stencil `depth`: its convention picks the camera that turns it
    /// into view depth.
    depth_rule: Option<DepthRule>,
    /// `hdr`, or `color` and `additive`.
    targets: Vec<rgraph_core::TextureHandle>,
    /// Draw only where this stencil is not marked.
    stencil: Option<rgraph_core::TextureHandle>,
    constants: Vec<(&'static str, f64)>,
}

#[cfg(feature = "gpu")]
mod gpu {
    use std::sync::Arc;

    use wgpu::BlendFactor::{One, OneMinusSrcAlpha, SrcAlpha, Zero};

    use super::{ParticleDispatch, ParticleDraw, TILE};
    use crate::common::depth::far_depth;
    use crate::common::gpu::bindings::TextureBindings;
    use crate::common::gpu::pipeline::{module, pipeline_layout, Pipelines};
    use crate::common::gpu::EDGE_STENCIL;
    use crate::common::gpu::{
        compute_pipeline, Compute, Frame, PipelineDesc, Recorded, Recorder, Render,
    };
    use crate::gpu_scene::{GpuScene, ParticleBuffer};
    use rgraph_scene::DepthConvention;

    /// What the plan and the depth convention decide.
    #[derive(Clone, PartialEq)]
    pub(crate) struct Key {
        targets: Vec<wgpu::TextureFormat>,
        stencil: Option<wgpu::TextureFormat>,
        convention: DepthConvention,
    }

    pub(crate) struct State {
        module: wgpu::ShaderModule,
        textures: TextureBindings,
        layout: wgpu::PipelineLayout,
        particles: ParticleBuffer,
        /// The blended and the additive pipeline.
        pipelines: Pipelines<Key, [wgpu::RenderPipeline; 2]>,
    }

    impl Recorder for ParticleDraw {
        type Stage = Render;
        type Scene = Arc<GpuScene>;
        type State = State;

        fn build(&self, frame: &Frame<'_, '_, Self>) -> Result<State, String> {
            let device = frame.device;
            let textures = TextureBindings::new(frame.resources, &[self.depth]);
            let particles = ParticleBuffer::new(device);
            let layouts = [
                Some(frame.scene.layout()),
                Some(&textures.layout),
                Some(particles.layout()),
            ];
            Ok(State {
                module: module(device, "particles", &self.source),
                layout: pipeline_layout(device, &layouts),
                textures,
                particles,
                pipelines: Pipelines::default(),
            })
        }

        fn record(&self, state: &mut State, frame: &mut Frame<'_, '_, Self>) -> Recorded {
            let pass = &mut *frame.pass;
            let (resources, device) = (frame.resources, frame.device);
            let inputs = frame.scene.inputs();
            state
                .particles
                .update(device, resources.queue, &inputs.emitters, &inputs.camera);
            let (blended, additive) = (state.particles.blended(), state.particles.additive());
            if blended.is_empty() && additive.is_empty() {
                return Ok(());
            }
            let convention = self.depth_rule.map_or(DepthConvention::ReversedZ, |rule| {
                rule.convention(resources.shape(self.depth.texture).format)
            });
            let key = Key {
                targets: self
                    .targets
                    .iter()
                    .map(|&h| resources.shape(h).format)
                    .collect(),
                stencil: self.stencil.map(|h| resources.shape(h).format),
                convention,
            };
            let (module, layout) = (&state.module, &state.layout);
            let [blend_pipeline, add_pipeline] = state.pipelines.get(key, |key| {
                let mut constants = self.constants.clone();
                if self.depth_rule.is_some() {
                    constants.push(("FAR_DEPTH", f64::from(far_depth(key.convention))));
                }
                let apart = key.targets.len() == 2;
                let build = |fragment, targets: &[Option<wgpu::ColorTargetState>]| {
                    PipelineDesc {
                        label: "particles",
                        layout,
                        module,
                        vertex: "vs_particle",
                        buffers: &[],
                        fragment,
                        constants: &constants,
                        targets,
                        cull: None,
                        depth_stencil: key.stencil.map(unmarked),
                        samples: 1,
                        mask: !0,
                    }
                    .build(device)
                };
                let target = |format, blend: Option<wgpu::BlendState>| {
                    Some(wgpu::ColorTargetState {
                        format,
                        blend,
                        write_mask: match blend {
                            Some(_) => wgpu::ColorWrites::ALL,
                            None => wgpu::ColorWrites::empty(),
                        },
                    })
                };
                match apart {
                    false => [
                        build("fs_blended", &[target(key.targets[0], Some(OVER))]),
                        build("fs_additive", &[target(key.targets[0], Some(ADD))]),
                    ],
                    true => [
                        build(
                            "fs_blended",
                            &[
                                target(key.targets[0], Some(OVER_TRANSMITTANCE)),
                                target(key.targets[1], None),
                            ],
                        ),
                        build(
                            "fs_additive_apart",
                            &[
                                target(key.targets[0], None),
                                target(key.targets[1], Some(ADD)),
                            ],
                        ),
                    ],
                }
            });
            pass.set_bind_group(0, frame.scene.bind_group(convention), &[]);
            pass.set_bind_group(1, &state.textures.bind_group(resources), &[]);
            pass.set_bind_group(2, state.particles.group(), &[]);
            pass.set_stencil_reference(EDGE_STENCIL);
            for (pipeline, instances) in [(blend_pipeline, blended), (add_pipeline, additive)] {
                if !instances.is_empty() {
                    pass.set_pipeline(pipeline);
                    pass.draw(0..6, instances);
                }
            }
            Ok(())
        }
    }

    /// The compute raster's device objects.
    pub(crate) struct ComputeState {
        textures: TextureBindings,
        particles: ParticleBuffer,
        pipeline: wgpu::ComputePipeline,
    }

    impl Recorder for ParticleDispatch {
        type Stage = Compute;
        type Scene = Arc<GpuScene>;
        type State = ComputeState;

        fn build(&self, frame: &Frame<'_, '_, Self>) -> Result<ComputeState, String> {
            let device = frame.device;
            let textures = TextureBindings::new(frame.resources, &self.inputs);
            let particles = ParticleBuffer::new(device);
            let layout = pipeline_layout(
                device,
                &[
                    Some(frame.scene.layout()),
                    Some(&textures.layout),
                    Some(particles.layout()),
                ],
            );
            let module = module(device, "particles (compute)", &self.source);
            let pipeline = compute_pipeline(
                device,
                "particles (compute)",
                &layout,
                &module,
                "cs_particles",
                &self.constants,
            );
            Ok(ComputeState {
                textures,
                particles,
                pipeline,
            })
        }

        fn record(&self, state: &mut ComputeState, frame: &mut Frame<'_, '_, Self>) -> Recorded {
            let pass = &mut *frame.pass;
            let resources = frame.resources;
            let inputs = frame.scene.inputs();
            state.particles.update(
                frame.device,
                resources.queue,
                &inputs.emitters,
                &inputs.camera,
            );
            // Every pixel of the targets is stored, particles or not: what the composite
            // reads.
            pass.set_pipeline(&state.pipeline);
            // A view depth needs no depth convention: the reversed-Z camera projects as
            // the fragment pass's does for one.
            let camera = frame.scene.bind_group(DepthConvention::ReversedZ);
            pass.set_bind_group(0, camera, &[]);
            pass.set_bind_group(1, &state.textures.bind_group(resources), &[]);
            pass.set_bind_group(2, state.particles.group(), &[]);
            let out = resources.shape(self.inputs[1].texture);
            pass.dispatch_workgroups(out.width.div_ceil(TILE), out.height.div_ceil(TILE), 1);
            Ok(())
        }
    }

    const fn component(
        src_factor: wgpu::BlendFactor,
        dst_factor: wgpu::BlendFactor,
    ) -> wgpu::BlendComponent {
        wgpu::BlendComponent {
            src_factor,
            dst_factor,
            operation: wgpu::BlendOperation::Add,
        }
    }

    /// Over the HDR image: colour `src * a + dst * (1 - a)`, its alpha kept.
    const OVER: wgpu::BlendState = wgpu::BlendState {
        color: component(SrcAlpha, OneMinusSrcAlpha),
        alpha: component(Zero, One),
    };
    /// Off screen (seed 001's Listing 23-3): colour as [`OVER`], alpha multiplied by
    /// `1 - a`, the transmittance.
    const OVER_TRANSMITTANCE: wgpu::BlendState = wgpu::BlendState {
        color: component(SrcAlpha, OneMinusSrcAlpha),
        alpha: component(Zero, OneMinusSrcAlpha),
    };
    /// Emissive particles: colour added, alpha kept.
    const ADD: wgpu::BlendState = wgpu::BlendState {
        color: component(One, One),
        alpha: component(Zero, One),
    };

    /// Passes where the mixed-resolution composite did not mark the stencil: the edge
    /// areas, which it left to this full-resolution pass.
    fn unmarked(format: wgpu::TextureFormat) -> wgpu::DepthStencilState {
        let test = wgpu::StencilFaceState {
            compare: wgpu::CompareFunction::NotEqual,
            fail_op: wgpu::StencilOperation::Keep,
            depth_fail_op: wgpu::StencilOperation::Keep,
            pass_op: wgpu::StencilOperation::Keep,
        };
        wgpu::DepthStencilState {
            format,
            depth_write_enabled: Some(false),
            depth_compare: Some(wgpu::CompareFunction::Always),
            stencil: wgpu::StencilState {
                front: test,
                back: test,
                read_mask: EDGE_STENCIL,
                write_mask: 0,
            },
            bias: Default::default(),
        }
    }
}
