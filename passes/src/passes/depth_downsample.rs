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
//! 3840x2160 for a 1920x1080 target (docs/design/particles.md, run particles-scale2), as a fragment
//! pass pays the ROPs for every pixel it writes.

use serde::Deserialize;

use rgraph_core::file::{Plugin, PluginError, Slots};
use rgraph_core::{Aspect, PassBuilder, PassKind};

use crate::common::fullscreen_compute::FullscreenCompute;
use crate::common::opaque_depth::OpaqueDepth;
use crate::common::plugin::Shared;
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
    /// Fixes the depth convention of a depth buffer; left out, it follows the depth
    /// format the compile picks, as the opaque passes' does.
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
        let (depth, samples) = OpaqueDepth::read(slots, pass, params.reversed_z)?;
        let want = Want::new("the downsampled view depth", textures::VIEW_DEPTH).samples(1);
        let (target, _) = textures::output(slots, pass, "view_depth", want, |pass, h, _| {
            pass.storage_write(h)
        })?;
        let stored = Input {
            binding: 1,
            texture: target,
            aspect: Aspect::All,
            texels: Texels::Store,
        };
        let dispatch = FullscreenCompute {
            label: "depth downsample",
            source: shaders::DEPTH_DOWNSAMPLE
                .compose_with(samples, &depth.wgsl())?
                .source()
                .to_owned(),
            entry: "cs_downsample",
            constants: vec![("TAPS", f64::from(params.taps))],
            inputs: vec![stored],
            reads_scene: true,
            target,
            depth: Some(depth),
        };
        self.0.record(pass, dispatch);
        Ok(())
    }
}
