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
//! and write an rgba16float texture in one dispatch); it writes every pixel once. On the
//! H200 such a pass costs about a millisecond at 3840x2160 (its ROPs): folded into the
//! visibility buffer's tiled resolve, where each sample's triangle is known, it would
//! cost nothing.

use serde::Deserialize;

use rgraph_core::file::{Plugin, PluginError, Slots};
use rgraph_core::types::{BlendComponent, BlendFactor, BlendOperation, BlendState};
use rgraph_core::{ColorLoad, PassBuilder, PassKind};

use crate::common::fullscreen::Fullscreen;
use crate::common::opaque_depth::OpaqueDepth;
use crate::common::plugin::Shared;
use crate::common::textures::{self, Want};
use crate::host::Background as Shown;
use crate::shaders;

pub struct Background(pub(crate) Shared);

#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BackgroundParams {}

/// The image gains the shader's colour, and its alpha becomes the shader's.
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
        let (depth, samples) = OpaqueDepth::read(slots, pass, None)?;
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
        let source = shaders::BACKGROUND
            .compose_with(samples, &depth.wgsl())?
            .source()
            .to_owned();
        let draw = Fullscreen {
            constants: vec![("ENVIRONMENT_BACKGROUND", f64::from(u8::from(environment)))],
            reads_scene: true,
            blend: Some(ADD_AND_MARK),
            depth: Some(depth),
            ..Fullscreen::new(
                "background",
                source,
                "fs_background",
                Vec::new(),
                Some(target),
            )
        };
        self.0.record(pass, draw);
        Ok(())
    }
}
