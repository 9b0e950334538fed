//! `depth_downsample`: the multisampled depth of the opaque passes as view depth at the
//! off-screen particles' size (seed 001 §23.3), for `particles` to test against.
//!
//! ```ron
//! (name: "depth downsample", plugin: "depth_downsample",
//!  params: (taps: 1),                        // 1: point sampling; n > 1: the maximum of
//!                                            // n x n; reversed_z optional
//!  inputs: { "depth": "depth" },             // the opaque passes' depth, any sample count;
//!                                            // or "samples": a compute rasteriser's keys
//!  outputs: { "view_depth": "particle_depth" })   // r32float, 1 sample, any size
//! ```
//!
//! A compute pass, an invocation per off-screen pixel, reading the depth aspect with
//! `textureLoad` (wgpu allows reading a multisampled depth, which DirectX 10 did not, so
//! the seed's MRT detour is not needed), or the keys, and storing view depth (along the
//! view direction, in world units; 1e30 where nothing was drawn), which needs no depth
//! convention downstream. `taps: 1` point-samples sample 0 of the pixel under the
//! off-screen pixel's centre: at scale 1 it is the value the full-resolution particle
//! pass reads. `taps: n` takes the maximum over every sample of n x n pixels spread over
//! the off-screen pixel's block (the seed took four, n = 2): the farthest depth, so
//! foreground silhouettes shrink by up to a block and particles behind them reach their
//! edges instead of stopping a block short (the halo of point sampling). A compute
//! rasteriser's pixel whose samples show one triangle is read at sample 0 alone (its
//! other samples are kept only at edges: visibility_compute's `other_samples`).
//!
//! In compute rather than as a full-screen draw: on the H200 the draw took 2.37 ms at
//! 3840x2160 for a 1920x1080 target (bench/results/gpu/particles-scale2), as a fragment
//! pass pays the ROPs for every pixel it writes.

use serde::Deserialize;

use graph_core::file::{Plugin, PluginError, Slots};
use graph_core::{Aspect, BufferHandle, PassBuilder, PassKind};

use crate::common::depth::DepthRule;
use crate::common::plugin::{Recording, Shared};
use crate::common::textures::{self, Input, Texels, Want};
use crate::common::visibility_samples;
use crate::shaders;

pub struct DepthDownsample(pub(crate) Shared);

/// The most taps per axis: 64 pixels per off-screen pixel, enough for scale 8.
pub const MAX_TAPS: u32 = 8;

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DepthDownsampleParams {
    /// 1 (the default): point sampling; 2 to [`MAX_TAPS`]: the maximum of taps x taps.
    #[serde(default = "one")]
    pub taps: u32,
    /// Fixes the depth convention; left out, it follows the depth format the compile
    /// picks, as the opaque passes' does.
    #[serde(default)]
    pub reversed_z: Option<bool>,
}

fn one() -> u32 {
    1
}

impl Plugin for DepthDownsample {
    const NAME: &'static str = "depth_downsample";
    type Params = DepthDownsampleParams;

    fn kind(&self, _: &DepthDownsampleParams) -> PassKind {
        PassKind::Compute
    }

    fn setup(
        &self,
        params: DepthDownsampleParams,
        pass: &mut PassBuilder<'_>,
        slots: &mut Slots<'_>,
    ) -> Result<(), PluginError> {
        if !(1..=MAX_TAPS).contains(&params.taps) {
            return Err(PluginError::Invalid(format!(
                "taps {} is not from 1 (point sampling) to {MAX_TAPS} (the maximum of \
                 {MAX_TAPS} x {MAX_TAPS} pixels per off-screen pixel)",
                params.taps
            )));
        }
        let (depth, samples, generated) = match slots.kind("samples") {
            Some(_) => {
                let (keys, samples) = visibility_samples::read(pass, slots, "samples")?;
                let generated = format!(
                    "{}\nfn sample_depth_at(pixel: vec2<i32>, s: u32) -> f32 {{\n    \
                     return sample_depth(pixel, s);\n}}\n",
                    shaders::KEYS
                );
                (Depth::Keys(keys), samples, generated)
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
                     fn sample_depth_at(pixel: vec2<i32>, s: u32) -> f32 {\n    \
                     return textureLoad(scene_depth, pixel, s);\n}\n\
                     fn one_surface(pixel: vec2<i32>) -> bool {\n    return false;\n}\n"
                    .to_owned();
                let rule = DepthRule::new(params.reversed_z);
                (Depth::Buffer(input, rule), desc.samples, generated)
            }
        };
        let want = Want::new("the downsampled view depth", textures::VIEW_DEPTH).samples(1);
        let (target, _) = textures::output(slots, pass, "view_depth", want, |pass, h, _| {
            pass.storage_write(h)
        })?;
        let draw = Downsample {
            source: shaders::DEPTH_DOWNSAMPLE
                .compose_with(samples, &generated)?
                .source()
                .to_owned(),
            depth,
            target: Input {
                binding: 1,
                texture: target,
                aspect: Aspect::All,
                texels: Texels::Store,
            },
            taps: params.taps,
        };
        self.0.record(pass, draw);
        Ok(())
    }
}

/// Where the pass reads the opaque scene's depth.
#[cfg_attr(not(feature = "gpu"), allow(dead_code))]
enum Depth {
    /// A depth buffer (group 1, binding 0) in the convention the rule gives its format.
    Buffer(Input, DepthRule),
    /// A compute rasteriser's keys: reversed-Z.
    Keys(BufferHandle),
}

#[cfg_attr(not(feature = "gpu"), allow(dead_code))]
struct Downsample {
    source: String,
    depth: Depth,
    target: Input,
    taps: u32,
}

impl Recording for Downsample {
    #[cfg(feature = "gpu")]
    fn record(self, scenes: std::sync::Arc<crate::gpu_scene::SceneCache>) -> graph_core::Record {
        graph_core::Record::Compute(gpu::record(self, scenes))
    }
}

#[cfg(feature = "gpu")]
mod gpu {
    use std::sync::Arc;

    use graph_core::gpu::ComputeContext;

    use super::{Depth, Downsample};
    use crate::common::depth::far_depth;
    use crate::common::gpu::{compute_pipeline, per_scene, GroupBuffers, InputPass};
    use crate::common::visibility_samples::{fits_binding, KEYS_BINDING};
    use crate::gpu_scene::SceneCache;
    use crate::scene::DepthConvention;

    pub(super) fn record(
        draw: Downsample,
        scenes: Arc<SceneCache>,
    ) -> Box<dyn FnMut(&mut ComputeContext<'_, '_>)> {
        let mut state = None;
        Box::new(move |ctx| {
            let resources = ctx.resources;
            let device = resources.device;
            let Some(scene) = scenes.for_frame(resources) else {
                return;
            };
            // The camera that unprojects the depth is the one of its convention.
            let (inputs, buffers, convention) = match &draw.depth {
                Depth::Buffer(input, rule) => {
                    let convention = rule.convention(resources.shape(input.texture).format);
                    (
                        vec![*input, draw.target],
                        GroupBuffers::default(),
                        convention,
                    )
                }
                Depth::Keys(keys) => {
                    if let Err(why) = fits_binding(device, resources.buffer(*keys)) {
                        return resources.fail(why);
                    }
                    let buffers = GroupBuffers {
                        read: vec![(KEYS_BINDING, *keys)],
                        owned: Vec::new(),
                    };
                    (vec![draw.target], buffers, DepthConvention::ReversedZ)
                }
            };
            let state: &mut InputPass<DepthConvention, wgpu::ComputePipeline> =
                per_scene(&mut state, &scene, || {
                    let label = "depth downsample";
                    InputPass::with_geometry(
                        resources,
                        label,
                        &draw.source,
                        Some(&scene),
                        &inputs,
                        &buffers,
                        false,
                    )
                });
            let (module, layout) = (&state.module, &state.layout);
            let pipeline = state.pipelines.get(convention, |&convention| {
                let constants = [
                    ("TAPS", f64::from(draw.taps)),
                    ("FAR_DEPTH", f64::from(far_depth(convention))),
                ];
                compute_pipeline(
                    device,
                    "depth downsample",
                    layout,
                    module,
                    "cs_downsample",
                    &constants,
                )
            });
            ctx.pass.set_pipeline(pipeline);
            ctx.pass
                .set_bind_group(0, scene.bind_group(convention), &[]);
            ctx.pass
                .set_bind_group(1, &state.inputs.bind_group(resources), &[]);
            let out = resources.shape(draw.target.texture);
            ctx.pass
                .dispatch_workgroups(out.width.div_ceil(8), out.height.div_ceil(8), 1);
        })
    }
}
