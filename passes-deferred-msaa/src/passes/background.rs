//! `background`: what a frame shows where its opaque passes drew nothing (the host's
//! [`Background`]), and how much of each pixel that is, for the passes after it.
//!
//! ```ron
//! (name: "background", plugin: "background",
//!  inputs: {
//!      "depth": "depth",        // the opaque passes' depth, any depth format and samples;
//!                               // or "samples": a compute rasteriser's keys
//!      "resolved": "resolved_hdr",
//!  },
//!  outputs: { "resolved": "resolved_bg" })   // rgba16float, 1 sample, modified in place
//! ```
//!
//! A full-screen draw onto the resolved HDR image, run after the opaque passes resolve
//! and before anything is composited over them (blended surfaces, particles), so what
//! shows through those shows the background. Per pixel it counts the samples that show
//! nothing (a depth at the far depth of the buffer's convention, or a key of 0) and adds
//! that share `t` of the environment's radiance through the pixel (level 0 of its cube
//! map: what a mirror reflects), exact for the box resolve every pipeline's opaque
//! passes end with: the resolved pixel is the mean of its samples, background ones
//! black. Its alpha becomes `t`, the background's transmittance, which the transparent
//! and particle composites multiply by theirs (transparent.rs's
//! `UNDER_TRANSMITTANCE`), so that tone mapping composites a colour background, or writes
//! `1 - t` as the output's alpha for a transparent one ([`Background::Color`],
//! [`Background::Transparent`]: this pass then adds nothing). Without a host (validating
//! a file) it draws nothing; with the host's background unset the pipelines leave the
//! pass out (condition `background`), and `rgraph render` refuses a `--background` for a
//! pipeline that has none.
//!
//! A fragment pass because it modifies the image in place (a compute pass could not read
//! and write an rgba16float texture in one dispatch); it writes every pixel once.

use serde::Deserialize;

use graph_core::file::{Plugin, PluginError, Slots};
use graph_core::types::{BlendComponent, BlendFactor, BlendOperation, BlendState};
use graph_core::{Aspect, BufferHandle, ColorLoad, PassBuilder, PassKind, TextureHandle};

use crate::common::plugin::{Recording, Shared};
use crate::common::textures::{self, Input, Texels, Want};
use crate::common::visibility_samples;
use crate::host::Background as Shown;
use crate::shaders;

pub struct Background(pub(crate) Shared);

#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BackgroundParams {}

/// Where the pass learns which samples show nothing.
#[cfg_attr(not(feature = "gpu"), allow(dead_code))]
enum Coverage {
    /// A depth buffer (group 1, binding 0), at the far depth of its format's convention.
    Depth(Input),
    /// A compute rasteriser's keys (visibility_samples.wgsl), 0 for nothing.
    Keys(BufferHandle),
}

/// The image gains the shader's colour, and its alpha becomes the shader's.
#[cfg_attr(not(feature = "gpu"), allow(dead_code))]
const ADD_AND_MARK: BlendState = BlendState {
    color: BlendComponent {
        src_factor: BlendFactor::One,
        dst_factor: BlendFactor::One,
        operation: BlendOperation::Add,
    },
    alpha: BlendComponent {
        src_factor: BlendFactor::One,
        dst_factor: BlendFactor::Zero,
        operation: BlendOperation::Add,
    },
};

impl Plugin for Background {
    const NAME: &'static str = "background";
    type Params = BackgroundParams;

    fn kind(&self, _: &BackgroundParams) -> PassKind {
        PassKind::Render
    }

    fn setup(
        &self,
        _: BackgroundParams,
        pass: &mut PassBuilder<'_>,
        slots: &mut Slots<'_>,
    ) -> Result<(), PluginError> {
        let (coverage, samples, generated) = match slots.kind("samples") {
            Some(_) => {
                let (keys, samples) = visibility_samples::read(pass, slots, "samples")?;
                let generated = format!(
                    "{}\nfn drawn(pixel: vec2<i32>, s: u32) -> bool {{\n    \
                     return sample_id(pixel, s) != 0u;\n}}\n\
                     fn coverage_size() -> vec2<f32> {{\n    return camera.viewport;\n}}\n",
                    shaders::KEYS
                );
                (Coverage::Keys(keys), samples, generated)
            }
            None => {
                let want = Want::new("the opaque passes' depth", textures::DEPTH_ANY);
                let (depth, desc) = textures::input(slots, pass, "depth", want)?;
                pass.sampled_aspect(depth, Aspect::DepthOnly);
                let input = Input {
                    binding: 0,
                    texture: depth,
                    aspect: Aspect::DepthOnly,
                    texels: Texels::Depth,
                };
                // Every sample is read: a depth buffer does not say where they agree.
                let generated = "@group(1) @binding(0) var scene_depth: GTexD;\n\
                     fn drawn(pixel: vec2<i32>, s: u32) -> bool {\n    \
                     return textureLoad(scene_depth, pixel, s) != FAR_DEPTH;\n}\n\
                     fn one_surface(pixel: vec2<i32>) -> bool {\n    return false;\n}\n\
                     fn coverage_size() -> vec2<f32> {\n    \
                     return vec2<f32>(textureDimensions(scene_depth));\n}\n"
                    .to_owned();
                (Coverage::Depth(input), desc.samples, generated)
            }
        };
        let want = Want::new("the resolved HDR image", textures::HDR).samples(1);
        let mut modifies = true;
        let (target, _) = textures::output(slots, pass, "resolved", want, |pass, h, m| {
            modifies = m;
            pass.color_output(h, ColorLoad::Load)
        })?;
        textures::must_modify(slots, "resolved", modifies, "adds the background to it")?;
        let environment = !matches!(
            self.0.overrides.background,
            Some(Shown::Color(_) | Shown::Transparent)
        );
        let draw = BackgroundDraw {
            source: shaders::BACKGROUND
                .compose_with(samples, &generated)?
                .source()
                .to_owned(),
            coverage,
            target,
            environment,
        };
        self.0.record(pass, draw);
        Ok(())
    }
}

/// The pass as set up: what its `gpu` module records.
#[cfg_attr(not(feature = "gpu"), allow(dead_code))]
struct BackgroundDraw {
    source: String,
    coverage: Coverage,
    target: TextureHandle,
    /// background.wgsl's ENVIRONMENT_BACKGROUND.
    environment: bool,
}

impl Recording for BackgroundDraw {
    #[cfg(feature = "gpu")]
    fn record(self, scenes: std::sync::Arc<crate::gpu_scene::SceneCache>) -> graph_core::Record {
        graph_core::Record::Render(gpu::record(self, scenes))
    }
}

#[cfg(feature = "gpu")]
mod gpu {
    //! Recording: one full-screen triangle, blended onto the image.

    use std::sync::Arc;

    use graph_core::gpu::RenderContext;

    use super::{BackgroundDraw, Coverage, ADD_AND_MARK};
    use crate::common::depth::{far_depth, DepthRule};
    use crate::common::gpu::{per_scene, GroupBuffers, InputPass, PipelineDesc};
    use crate::common::visibility_samples::{fits_binding, KEYS_BINDING};
    use crate::gpu_scene::SceneCache;
    use crate::scene::DepthConvention;

    /// The target's format and the far depth the coverage is read against.
    #[derive(Clone, PartialEq)]
    struct Key {
        target: wgpu::TextureFormat,
        convention: DepthConvention,
    }

    pub(super) fn record(
        draw: BackgroundDraw,
        scenes: Arc<SceneCache>,
    ) -> Box<dyn FnMut(&mut RenderContext<'_, '_>)> {
        let mut state = None;
        Box::new(move |ctx| {
            let resources = ctx.resources;
            let Some(scene) = scenes.for_frame(resources) else {
                return;
            };
            let (inputs, buffers, convention) = match &draw.coverage {
                Coverage::Depth(input) => {
                    let format = resources.shape(input.texture).format;
                    let convention = DepthRule::new(None).convention(format);
                    (vec![*input], GroupBuffers::default(), convention)
                }
                Coverage::Keys(keys) => {
                    if let Err(why) = fits_binding(resources.device, resources.buffer(*keys)) {
                        return resources.fail(why);
                    }
                    let buffers = GroupBuffers {
                        read: vec![(KEYS_BINDING, *keys)],
                        owned: Vec::new(),
                    };
                    (Vec::new(), buffers, DepthConvention::ReversedZ)
                }
            };
            let state: &mut InputPass<Key> = per_scene(&mut state, &scene, || {
                InputPass::with_geometry(
                    resources,
                    "background",
                    &draw.source,
                    Some(&scene),
                    &inputs,
                    &buffers,
                    false,
                )
            });
            let key = Key {
                target: resources.shape(draw.target).format,
                convention,
            };
            let (module, layout) = (&state.module, &state.layout);
            let pipeline = state.pipelines.get(key, |key| {
                let constants = [
                    ("FAR_DEPTH", f64::from(far_depth(key.convention))),
                    (
                        "ENVIRONMENT_BACKGROUND",
                        f64::from(u8::from(draw.environment)),
                    ),
                ];
                PipelineDesc {
                    label: "background",
                    layout,
                    module,
                    vertex: "vs_fullscreen",
                    buffers: &[],
                    fragment: "fs_background",
                    constants: &constants,
                    targets: &[Some(wgpu::ColorTargetState {
                        format: key.target,
                        blend: Some(ADD_AND_MARK),
                        write_mask: wgpu::ColorWrites::ALL,
                    })],
                    cull: None,
                    depth_stencil: None,
                    samples: 1,
                    mask: !0,
                }
                .build(resources.device)
            });
            ctx.pass.set_pipeline(pipeline);
            // The environment's direction only: either camera unprojects it.
            ctx.pass
                .set_bind_group(0, scene.bind_group(DepthConvention::ReversedZ), &[]);
            ctx.pass
                .set_bind_group(1, &state.inputs.bind_group(resources), &[]);
            ctx.pass.draw(0..3, 0..1);
        })
    }
}
