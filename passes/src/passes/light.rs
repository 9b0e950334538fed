//! `light_nonedge` and `light_edge`: add every light's contribution to the multisampled
//! HDR target, once per pixel where the edge pass left the stencil clear and once per
//! sample where it marked 0x80 (seed 000's two shading passes).
//!
//! ```ron
//! (name: "light_edge", plugin: "light_edge",
//!  params: (mode: sample_index, volumes: true),   // these defaults
//!                     // (or mode: sample_mask; volumes: false; reversed_z: true or false,
//!                     // which left out follows the depth format)
//!  inputs: {
//!      "albedo": "albedo", "normal": "normal", "material": "material",
//!      "view_depth": "view_depth",
//!      "depth": "depth_edges",   // the depth-stencil: attached read-only, both aspects
//!      "hdr": "hdr",             // also an output: the pass adds to it
//!      "ao": "ao",               // optional: ssao_blur's occlusion (r8unorm, 1 sample),
//!                                // which scales the ambient and environment light only
//!      "shadows": "shadow_atlas", // optional: shadow_maps's atlas (depth32float), which
//!                                // scales each shadowed light (common/shadows.rs)
//!      "specular": "specular", "clearcoat": "clearcoat", "sheen": "sheen",
//!                                // the G-buffer's material layers, where it has them
//!                                // (common/gbuffer_layers.rs), usually `optional`
//!  },
//!  outputs: { "hdr": "hdr_edges" })
//! (name: "light_nonedge", plugin: "light_nonedge",
//!  params: (volumes: true, samples: first),   // or samples: average; reversed_z
//!  //  both take `accumulate: shaded` (the default) or `light`: the light pre-pass's
//!  //  light buffer in "hdr", from the thin G-buffer without "albedo" (light_prepass.rs),
//!  //  and with it an optional "lobes" slot (in inputs and outputs): the lobes buffer
//!  //  its material layers' clear coat and sheen add to
//!  inputs: { /* the same slots */ "hdr": "hdr_edges" },
//!  outputs: { "hdr": "hdr_lit" })
//! ```
//!
//! Directional lights and the scene's ambient term are one full-screen triangle at the far
//! plane, depth-tested so pixels without geometry are skipped. Point lights draw a sphere
//! and spot lights a cone circumscribing their reach (a sphere past 45°, where the cone
//! grows wider than the range); from outside, front faces with the
//! normal depth test, and when the camera's near plane may cut the volume (a conservative
//! test with the near plane's corner distance as margin), back faces with the depth test
//! reversed; when those back faces may reach beyond a finite far plane, where they would
//! be clipped, the light is drawn full screen (tests/deferred_volumes_gpu.rs covers every
//! case). With `volumes: false` every light is a full-screen triangle instead: slower,
//! and the reference the volumes must match (the falloff window is exactly zero outside
//! a volume: shaded per sample the two are bit-identical, tests/deferred_lit.rs). Shading
//! is Lambert plus GGX metallic-roughness, with the material layers the G-buffer holds
//! (each decoded by gbuffer_layers.wgsl, as every G-buffer lighting pass decodes it);
//! unlit pixels are skipped (the G-buffer put their color in `hdr`). Every contribution is finite and at most the
//! half-float maximum.
//!
//! `light_nonedge` shades from sample 0 at the pixel center and writes every sample the
//! volume covers. With `samples: average` it shades every sample and writes their
//! average instead: seed 004's on-the-fly resolve, a baseline that darkens edges
//! (pipelines/deferred_onthefly_resolve_4x.ron). `light_edge` shades each sample at its own position and depth (read
//! from the read-only depth attachment, as the volume test saw it): `sample_index` runs
//! the fragment shader per sample (`@builtin(sample_index)`); `sample_mask` draws everything once per sample with the
//! pipeline's multisample mask `1 << i` and the sample to read as a pipeline constant
//! (DX10.0's method; writing `@builtin(sample_mask)` is avoided, gfx-rs/wgpu#7311). Both
//! give bit-identical images. With one sample per pixel `light_edge` is omitted from
//! every plan, as `edge_stencil` is: there are no edge pixels, and `light_nonedge`
//! shades every pixel.

use serde::Deserialize;

use rgraph_core::file::{Plugin, PluginError, Slots};
use rgraph_core::{Aspect, AspectAccess, ColorLoad, PassBuilder, PassKind, TextureHandle};

use crate::common::ao;
use crate::common::depth::DepthRule;
use crate::common::gbuffer_layers::{self, LayerSet};
use crate::common::plugin::{yes, Shared, ONE_SAMPLE};
use crate::common::shadows;
use crate::common::textures::{self, Input, Texels, Want, GBUFFER_INPUTS};
use crate::shaders;

pub struct LightNonEdge(pub(crate) Shared);
pub struct LightEdge(pub(crate) Shared);

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LightNonEdgeParams {
    /// Fixes the depth convention; left out, it follows the depth format the compile
    /// picks: reversed-Z for float depth, standard Z for unorm depth.
    #[serde(default)]
    pub reversed_z: Option<bool>,
    /// Draw point and spot lights as volumes; `false` draws each full screen, the exact
    /// (and slow) reference the volumes must match.
    #[serde(default = "yes")]
    pub volumes: bool,
    #[serde(default)]
    pub samples: PixelSamples,
    #[serde(default)]
    pub accumulate: Accumulate,
}

/// What the light passes add up in their `hdr` slot.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Accumulate {
    /// The lit colour, from the full G-buffer.
    #[default]
    Shaded,
    /// The light pre-pass's light buffer (light_prepass.wgsl), from the thin G-buffer
    /// (`normal`, `material`, `view_depth`; no `albedo`): diffuse light and the
    /// luminance of a dielectric's specular, before the material is applied
    /// (passes/light_prepass.rs).
    Light,
}

/// Which G-buffer samples `light_nonedge` shades a pixel from.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PixelSamples {
    /// Sample 0 (seed 000's per-pixel pass).
    #[default]
    First,
    /// All of them, averaged after shading (seed 004's on-the-fly resolve).
    Average,
}

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LightEdgeParams {
    #[serde(default)]
    pub mode: EdgeMode,
    /// Fixes the depth convention; left out, it follows the depth format the compile
    /// picks: reversed-Z for float depth, standard Z for unorm depth.
    #[serde(default)]
    pub reversed_z: Option<bool>,
    /// As for `light_nonedge`.
    #[serde(default = "yes")]
    pub volumes: bool,
    /// As for `light_nonedge`.
    #[serde(default)]
    pub accumulate: Accumulate,
}

/// How `light_edge` shades each sample.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum EdgeMode {
    #[default]
    SampleIndex,
    SampleMask,
}

/// Which pixels a light pass shades, and how often.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(crate) enum Frequency {
    /// Stencil without 0x80, once per pixel from the given samples.
    Pixel(PixelSamples),
    /// Stencil 0x80, once per sample.
    Sample(EdgeMode),
}

/// A light pass as set up: what its `gpu` module records.
#[cfg_attr(not(feature = "gpu"), allow(dead_code))]
pub(crate) struct LightDraw {
    pub source: String,
    pub depth_rule: DepthRule,
    pub frequency: Frequency,
    pub volumes: bool,
    pub hdr: TextureHandle,
    /// The light pre-pass's lobes buffer, the second target, where the pass adds to it.
    pub lobes: Option<TextureHandle>,
    pub depth: TextureHandle,
    pub inputs: Vec<Input>,
}

impl Plugin for LightNonEdge {
    const NAME: &'static str = "light_nonedge";
    type Params = LightNonEdgeParams;

    fn kind(&self, _: &LightNonEdgeParams) -> PassKind {
        PassKind::Render
    }

    fn setup(
        &self,
        params: LightNonEdgeParams,
        pass: &mut PassBuilder<'_>,
        slots: &mut Slots<'_>,
    ) -> Result<(), PluginError> {
        let light = LightPass {
            frequency: Frequency::Pixel(params.samples),
            reversed_z: params.reversed_z,
            volumes: params.volumes,
            accumulate: params.accumulate,
        };
        light.setup(&self.0, pass, slots)
    }
}

impl Plugin for LightEdge {
    const NAME: &'static str = "light_edge";
    type Params = LightEdgeParams;

    fn kind(&self, _: &LightEdgeParams) -> PassKind {
        PassKind::Render
    }

    fn setup(
        &self,
        params: LightEdgeParams,
        pass: &mut PassBuilder<'_>,
        slots: &mut Slots<'_>,
    ) -> Result<(), PluginError> {
        let light = LightPass {
            frequency: Frequency::Sample(params.mode),
            reversed_z: params.reversed_z,
            volumes: params.volumes,
            accumulate: params.accumulate,
        };
        light.setup(&self.0, pass, slots)
    }
}

/// Either light pass's parameters.
struct LightPass {
    frequency: Frequency,
    reversed_z: Option<bool>,
    volumes: bool,
    accumulate: Accumulate,
}

impl LightPass {
    /// Sets up the pass and gives it its recording (the host's shadow filter from
    /// `shared`): per set of material layers the plan keeps, and with and without an
    /// optional shadow atlas. `light_edge` omits itself at one sample per pixel instead.
    fn setup(
        self,
        shared: &Shared,
        pass: &mut PassBuilder<'_>,
        slots: &mut Slots<'_>,
    ) -> Result<(), PluginError> {
        let LightPass {
            frequency,
            reversed_z,
            volumes,
            accumulate,
        } = self;
        let want = Want::new("the G-buffer's depth-stencil", textures::DEPTH_STENCIL);
        let (depth, desc) = textures::input(slots, pass, "depth", want)?;
        pass.depth_stencil(depth, AspectAccess::ReadOnly, AspectAccess::ReadOnly);
        let samples = desc.samples;
        let mut inputs = Vec::new();
        if let Frequency::Sample(_) = frequency {
            // Per-sample shading reads each sample's depth, which the read-only attachment
            // allows in the same pass (notes/wgpu30.md).
            pass.sampled_aspect(depth, Aspect::DepthOnly);
            inputs.push(Input {
                binding: 5,
                texture: depth,
                aspect: Aspect::DepthOnly,
                texels: Texels::Depth,
            });
        }
        // The light pre-pass's thin G-buffer has no albedo.
        let reads = GBUFFER_INPUTS
            .into_iter()
            .filter(|(slot, ..)| accumulate == Accumulate::Shaded || *slot != "albedo");
        for (slot, what, formats, binding) in reads {
            let want = Want::new(what, formats).samples(samples);
            inputs.push(textures::sampled(slots, pass, slot, want, binding)?.0);
        }
        let layers = gbuffer_layers::inputs(slots, pass, samples, &mut inputs)?;
        let want = match accumulate {
            Accumulate::Shaded => Want::new("the HDR target", textures::HDR),
            Accumulate::Light => Want::new("the light buffer", textures::HDR),
        };
        let want = want.samples(samples);
        let mut modifies = true;
        let (hdr, _) = textures::output(slots, pass, "hdr", want, |pass, h, m| {
            modifies = m;
            pass.color_output(h, ColorLoad::Load)
        })?;
        textures::must_modify(slots, "hdr", modifies, "adds light to it")?;
        let lobes = match (slots.kind("lobes"), accumulate) {
            (None, _) => None,
            (Some(_), Accumulate::Shaded) => {
                return Err(PluginError::Invalid(
                    "\"lobes\" is the light pre-pass's lobes buffer, which only \
                     `accumulate: light` adds to"
                        .into(),
                ))
            }
            (Some(_), Accumulate::Light) => {
                let want = Want::new("the lobes buffer", textures::HDR).samples(samples);
                let mut modifies = true;
                let (lobes, _) = textures::output(slots, pass, "lobes", want, |pass, h, m| {
                    modifies = m;
                    pass.color_output(h, ColorLoad::Load)
                })?;
                textures::must_modify(slots, "lobes", modifies, "adds light to it")?;
                Some(lobes)
            }
        };
        // The light pre-pass's ambient light is the material pass's, so no AO there (an
        // "ao" slot is left unread, which the file loader reports).
        let ao = match accumulate {
            Accumulate::Shaded => ao::input(slots, pass)?,
            Accumulate::Light => None,
        };
        inputs.extend(ao);
        let generated = ao::wgsl(ao.as_ref()) + &outputs_wgsl(lobes.is_some());
        let shadows = shadows::input(slots, pass)?;
        if matches!(frequency, Frequency::Sample(_)) && samples == 1 {
            pass.omit(ONE_SAMPLE);
            return Ok(());
        }
        let (optional_atlas, filter) = (shadows::optional(slots), shared.overrides.shadows.filter);
        let targets = layers.clone();
        let make = move |set: LayerSet| {
            shadows::variants(optional_atlas, shadows, |atlas| {
                let generated = generated.clone()
                    + &shadows::wgsl(atlas, 1, filter)
                    + &gbuffer_layers::read_wgsl(set);
                let source = match accumulate {
                    Accumulate::Shaded => shaders::LIGHT.compose_with(samples, &generated)?,
                    Accumulate::Light => {
                        shaders::LIGHT_PREPASS.compose_with(samples, &generated)?
                    }
                };
                let mut inputs = set.inputs(&targets, &inputs);
                inputs.extend(atlas.copied());
                Ok(LightDraw {
                    source: source.source().to_owned(),
                    depth_rule: DepthRule::new(reversed_z),
                    frequency,
                    volumes,
                    hdr,
                    lobes,
                    depth,
                    inputs,
                })
            })
        };
        shared.record_kept(pass, layers, make)
    }
}

/// light.wgsl's `LightOut` and `light_out`: the light or lit colour at location 0, and
/// where the pass has `lobes` (the light pre-pass's lobes buffer), the lobes at 1.
fn outputs_wgsl(lobes: bool) -> String {
    let (field, value) = match lobes {
        true => ("    @location(1) lobes: vec4<f32>,\n", ", s.lobes"),
        false => ("", ""),
    };
    format!(
        "// Generated: the targets this light pass adds to.\n\
         struct LightOut {{\n    @location(0) light: vec4<f32>,\n{field}}}\n\n\
         fn light_out(s: SampleLight) -> LightOut {{\n    return LightOut(s.light{value});\n}}\n"
    )
}

#[cfg(feature = "gpu")]
mod gpu {
    //! Recording a light pass: the full-screen draw for directional lights and ambient, then
    //! each point or spot light's volume, once (per pixel or `sample_index`) or once per
    //! sample with the multisample mask (`sample_mask`).
    //!
    //! Pipelines are made on first use, so a pass builds the full-screen one only when some
    //! directional light emits or there is ambient, and volume ones only when a point or
    //! spot light does ([`GpuScene::has_fullscreen_lights`], [`GpuScene::volume_lights`]);
    //! each is compiled for the scene's light kinds (its shader variant, variant.rs),
    //! which the key holds.

    use std::sync::Arc;

    use super::{EdgeMode, Frequency, LightDraw, PixelSamples};
    use crate::common::depth::far_depth;
    use crate::common::gpu::EDGE_STENCIL;
    use crate::common::gpu::{
        additive, Frame, InputPass, PipelineDesc, Recorded, Recorder, Render,
    };
    use crate::gpu_scene::{volumes, GpuScene};
    use crate::variant::{GatedShader, Variant};
    use rgraph_scene::DepthConvention;

    /// What a light draw rasterizes, and so its depth test and culling.
    #[derive(Copy, Clone, Debug, PartialEq, Eq)]
    enum Geometry {
        /// A full-screen triangle at the far plane: passes wherever geometry was drawn. For
        /// directional lights and ambient, or (`light` true) one point or spot light.
        FarPlane { light: bool },
        /// A volume's front faces, in front of the surface.
        FrontFaces,
        /// A volume's back faces, behind the surface (the camera may be inside). Never where
        /// they may reach beyond a finite far plane: the light is drawn full screen there.
        BackFaces,
    }

    #[derive(Clone, PartialEq)]
    pub(crate) struct Key {
        hdr: wgpu::TextureFormat,
        lobes: Option<wgpu::TextureFormat>,
        depth: wgpu::TextureFormat,
        samples: u32,
        geometry: Geometry,
        /// `sample_mask` mode: the one sample the pipeline shades and writes.
        sample: Option<u32>,
        variant: Variant,
    }

    impl Recorder for LightDraw {
        type Stage = Render;
        type Scene = Arc<GpuScene>;
        type State = InputPass<Key>;

        fn build(&self, frame: &Frame<'_, '_, Self>) -> Result<Self::State, String> {
            let scene = Some(&*frame.scene);
            Ok(InputPass::new(
                frame.resources,
                "light",
                &self.source,
                scene,
                &self.inputs,
            ))
        }

        fn record(&self, state: &mut Self::State, frame: &mut Frame<'_, '_, Self>) -> Recorded {
            let pass = &mut *frame.pass;
            let (resources, device, scene) = (frame.resources, frame.device, &frame.scene);
            let size = resources.output_size();
            let (hdr, depth) = (resources.shape(self.hdr), resources.shape(self.depth));
            let lobes = self.lobes.map(|h| resources.shape(h).format);
            let passes: Vec<Option<u32>> = match self.frequency {
                Frequency::Sample(EdgeMode::SampleMask) => (0..hdr.samples).map(Some).collect(),
                Frequency::Pixel(_) | Frequency::Sample(EdgeMode::SampleIndex) => vec![None],
            };
            let convention = self.depth_rule.convention(depth.format);
            pass.set_bind_group(0, scene.bind_group(convention), &[]);
            pass.set_bind_group(1, &state.inputs.bind_group(resources), &[]);
            pass.set_stencil_reference(EDGE_STENCIL);
            let (module, layout) = (&state.module, &state.layout);
            let variant = frame.scenes.variant(GatedShader::Light);
            let mut use_pipeline = |pass: &mut wgpu::RenderPass<'_>, geometry, sample| {
                let key = Key {
                    hdr: hdr.format,
                    lobes,
                    depth: depth.format,
                    samples: hdr.samples,
                    geometry,
                    sample,
                    variant: variant.clone(),
                };
                let pipeline = state.pipelines.get(key, |key| {
                    let targets: Vec<_> = [Some(key.hdr), key.lobes]
                        .into_iter()
                        .flatten()
                        .map(|format| Some(additive(format)))
                        .collect();
                    let mut constants = vec![
                        ("FAR_DEPTH", f64::from(far_depth(convention))),
                        ("SAMPLE", f64::from(key.sample.unwrap_or(0))),
                    ];
                    constants.extend(key.variant.constants());
                    let volume_buffers = [Some(volumes::VERTEX_LAYOUT)];
                    PipelineDesc {
                        label: "light",
                        layout,
                        module,
                        vertex: match key.geometry {
                            Geometry::FarPlane { light: false } => "vs_directional",
                            Geometry::FarPlane { light: true } => "vs_fullscreen_light",
                            Geometry::FrontFaces | Geometry::BackFaces => "vs_volume",
                        },
                        buffers: match key.geometry {
                            Geometry::FarPlane { .. } => &[],
                            Geometry::FrontFaces | Geometry::BackFaces => &volume_buffers,
                        },
                        fragment: match (self.frequency, key.sample) {
                            (Frequency::Pixel(PixelSamples::First), _) => "fs_pixel",
                            (Frequency::Pixel(PixelSamples::Average), _) => "fs_pixel_average",
                            (Frequency::Sample(_), None) => "fs_sample",
                            (Frequency::Sample(_), Some(_)) => "fs_one_sample",
                        },
                        constants: &constants,
                        targets: &targets,
                        cull: match key.geometry {
                            Geometry::FarPlane { .. } => None,
                            Geometry::FrontFaces => Some(wgpu::Face::Back),
                            Geometry::BackFaces => Some(wgpu::Face::Front),
                        },
                        depth_stencil: Some(depth_stencil(key, convention, self.frequency)),
                        samples: key.samples,
                        mask: key.sample.map_or(!0, |s| 1 << s),
                    }
                    .build(device)
                });
                pass.set_pipeline(pipeline);
            };
            for sample in passes {
                if scene.has_fullscreen_lights() {
                    use_pipeline(pass, Geometry::FarPlane { light: false }, sample);
                    pass.draw(0..3, 0..1);
                }
                for light in scene.volume_lights() {
                    let instance = light.index..light.index + 1;
                    let geometry = if !self.volumes {
                        Geometry::FarPlane { light: true }
                    } else if !scene.camera_may_be_inside(light, size) {
                        Geometry::FrontFaces
                    } else if scene.far_plane_may_cut(light) {
                        // Its back faces would be clipped away beyond the far plane.
                        Geometry::FarPlane { light: true }
                    } else {
                        Geometry::BackFaces
                    };
                    use_pipeline(pass, geometry, sample);
                    if geometry == (Geometry::FarPlane { light: true }) {
                        pass.draw(0..3, instance);
                        continue;
                    }
                    let mesh = scene.volume_mesh(light.shape);
                    pass.set_vertex_buffer(0, mesh.vertices.slice(..));
                    pass.set_index_buffer(mesh.indices.slice(..), wgpu::IndexFormat::Uint32);
                    pass.draw_indexed(0..mesh.index_count, 0, light.index..light.index + 1);
                }
            }
            Ok(())
        }
    }

    /// Read-only depth and stencil: the depth test per [`Geometry`], and the stencil test
    /// that splits edge pixels (0x80) from the rest.
    fn depth_stencil(
        key: &Key,
        convention: DepthConvention,
        frequency: Frequency,
    ) -> wgpu::DepthStencilState {
        use wgpu::CompareFunction as C;
        let reversed = convention == DepthConvention::ReversedZ;
        // "In front of" is Greater with reversed Z, Less without.
        let (in_front, behind) = match reversed {
            true => (C::GreaterEqual, C::LessEqual),
            false => (C::LessEqual, C::GreaterEqual),
        };
        let depth_compare = match key.geometry {
            // The far plane is behind every drawn surface, and no surface is behind it.
            Geometry::FarPlane { .. } => match reversed {
                true => C::Less,
                false => C::Greater,
            },
            Geometry::FrontFaces => in_front,
            Geometry::BackFaces => behind,
        };
        let test = wgpu::StencilFaceState {
            compare: match frequency {
                Frequency::Pixel(_) => C::NotEqual,
                Frequency::Sample(_) => C::Equal,
            },
            fail_op: wgpu::StencilOperation::Keep,
            depth_fail_op: wgpu::StencilOperation::Keep,
            pass_op: wgpu::StencilOperation::Keep,
        };
        wgpu::DepthStencilState {
            format: key.depth,
            depth_write_enabled: Some(false),
            depth_compare: Some(depth_compare),
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
