//! `depth_downsample`: the multisampled depth of the opaque passes as view depth at the
//! off-screen particles' size (seed 001 §23.3), for `particles` to test against.
//!
//! ```ron
//! (name: "depth downsample", plugin: "depth_downsample",
//!  params: (taps: 1),                        // 1: point sampling; n > 1: the maximum of
//!                                            // n x n; reversed_z optional
//!  inputs: { "depth": "depth" },             // the depth-stencil, any sample count
//!  outputs: { "view_depth": "particle_depth" })   // r32float, 1 sample, any size
//! ```
//!
//! A full-screen draw at the output's size, one fragment per off-screen pixel, reading
//! the depth aspect with `textureLoad` (wgpu allows sampling a multisampled depth, which
//! DirectX 10 did not, so the seed's MRT detour is not needed) and writing view depth
//! (along the view direction, in world units; 1e30 where nothing was drawn), which
//! needs no depth convention downstream. `taps: 1` point-samples sample 0 of the pixel
//! under the off-screen pixel's centre: at scale 1 it is the value the full-resolution
//! particle pass reads. `taps: n` takes the maximum over every sample of n x n pixels
//! spread over the off-screen pixel's block (the seed took four, n = 2): the farthest
//! depth, so foreground silhouettes shrink by up to a block and particles behind them
//! reach their edges instead of stopping a block short (the halo of point sampling).

use serde::Deserialize;

use graph_core::file::{Plugin, PluginError, Slots};
use graph_core::{Aspect, PassBuilder, PassKind};

use crate::common::depth::DepthRule;
use crate::common::plugin::{Recording, Shared};
use crate::common::textures::{self, Input, Texels, Want};
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
        PassKind::Render
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
        let want = Want::new("the opaque passes' depth", textures::DEPTH_STENCIL);
        let (depth, desc) = textures::input(slots, pass, "depth", want)?;
        pass.sampled_aspect(depth, Aspect::DepthOnly);
        let want = Want::new("the downsampled view depth", textures::VIEW_DEPTH).samples(1);
        let (target, _) = textures::color_output(slots, pass, "view_depth", want, [0.0; 4])?;
        let draw = Downsample {
            source: shaders::DEPTH_DOWNSAMPLE
                .compose(desc.samples)?
                .source()
                .to_owned(),
            depth: Input {
                binding: 0,
                texture: depth,
                aspect: Aspect::DepthOnly,
                texels: Texels::Depth,
            },
            depth_rule: DepthRule::new(params.reversed_z),
            target,
            taps: params.taps,
        };
        self.0.record(pass, draw);
        Ok(())
    }
}

#[cfg_attr(not(feature = "gpu"), allow(dead_code))]
struct Downsample {
    source: String,
    depth: Input,
    depth_rule: DepthRule,
    target: graph_core::TextureHandle,
    taps: u32,
}

impl Recording for Downsample {
    #[cfg(feature = "gpu")]
    fn record(self, scenes: std::sync::Arc<crate::gpu_scene::SceneCache>) -> graph_core::Record {
        graph_core::Record::Render(gpu::record(self, scenes))
    }
}

#[cfg(feature = "gpu")]
mod gpu {
    use std::sync::Arc;

    use graph_core::gpu::RenderContext;

    use super::Downsample;
    use crate::common::depth::far_depth;
    use crate::common::gpu::{per_scene, InputPass, PipelineDesc};
    use crate::gpu_scene::SceneCache;
    use crate::scene::DepthConvention;

    /// The camera that unprojects the depth is the one of its convention.
    #[derive(Clone, PartialEq)]
    struct Key {
        target: wgpu::TextureFormat,
        convention: DepthConvention,
    }

    pub(super) fn record(
        draw: Downsample,
        scenes: Arc<SceneCache>,
    ) -> Box<dyn FnMut(&mut RenderContext<'_, '_>)> {
        let mut state = None;
        Box::new(move |ctx| {
            let resources = ctx.resources;
            let Some(scene) = scenes.for_frame(resources) else {
                return;
            };
            let state: &mut InputPass<Key> = per_scene(&mut state, &scene, || {
                let label = "depth downsample";
                InputPass::new(resources, label, &draw.source, Some(&scene), &[draw.depth])
            });
            let depth = resources.shape(draw.depth.texture).format;
            let convention = draw.depth_rule.convention(depth);
            let key = Key {
                target: resources.shape(draw.target).format,
                convention,
            };
            let (module, layout) = (&state.module, &state.layout);
            let pipeline = state.pipelines.get(key, |key| {
                let constants = [
                    ("TAPS", f64::from(draw.taps)),
                    ("FAR_DEPTH", f64::from(far_depth(key.convention))),
                ];
                PipelineDesc {
                    label: "depth downsample",
                    layout,
                    module,
                    vertex: "vs_block",
                    buffers: &[],
                    fragment: "fs_downsample",
                    constants: &constants,
                    targets: &[Some(key.target.into())],
                    cull: None,
                    depth_stencil: None,
                    samples: 1,
                    mask: !0,
                }
                .build(resources.device)
            });
            ctx.pass.set_pipeline(pipeline);
            ctx.pass
                .set_bind_group(0, scene.bind_group(convention), &[]);
            ctx.pass
                .set_bind_group(1, &state.inputs.bind_group(resources), &[]);
            ctx.pass.draw(0..3, 0..1);
        })
    }
}
