//! `tonemap`: exposure and a tone-mapping operator from the resolved HDR target into the
//! displayable output.
//!
//! ```ron
//! (name: "tonemap", plugin: "tonemap",
//!  params: (operator: aces, exposure: 1.0,    // these defaults; or none | reinhard
//!           stage: fragment),                 // or compute
//!  inputs: { "hdr": "resolved" },              // rgba16float, 1 sample
//!  outputs: { "color": "color" })              // rgba8unorm-srgb (or rgba8unorm), 1 sample
//! ```
//!
//! `stage: compute` runs it as a compute pass writing an `rgba8unorm` storage texture,
//! sRGB-encoded in the shader (no sRGB format is a storage format): the bytes an sRGB
//! target holds, which a reader must take as sRGB. A full-screen fragment pass pays the
//! ROPs for every pixel, and on the H200 the fragment pass takes 1.27 ms at 3840x2160.
//!
//! With an `"exposure"` input (the 1x1 r32float texture `auto_exposure` writes), the pass
//! multiplies the metered exposure by `exposure` (then a compensation): what the host's
//! auto exposure runs, under the condition `auto_exposure`.
//!
//! The host's background ([`Background`]): a colour is composited under the image here,
//! in linear light, by the background's transmittance that a `background` pass left in
//! the HDR image's alpha (and the passes compositing over it multiplied); transparency
//! writes one minus it as the output's alpha, the colour unpremultiplied (tone mapped as
//! the surfaces' own). The environment is in the image already.
//!
//! `none` clamps the exposed linear color to [0, 1]; `reinhard` is `c / (1 + c)` per
//! channel; `aces` is Narkowicz's fit of the ACES filmic curve. An sRGB output encodes
//! the result. The host's overrides replace `operator` and `exposure` when set. With a
//! host, the frame's exposure factor (`FrameInputs::exposure`, from the scene's light
//! info, group 0) multiplies the result each frame: a uniform, not the pipeline constant
//! `exposure` becomes, so a new value every frame builds no pipeline.

use serde::Deserialize;

use rgraph_core::file::{Plugin, PluginError, Slots};
use rgraph_core::types::TextureFormat;
use rgraph_core::{Aspect, PassBuilder, PassKind};

use super::resolve::{exposure, one};
use crate::common::fullscreen::Fullscreen;
use crate::common::fullscreen_compute::FullscreenCompute;
use crate::common::plugin::Shared;
use crate::common::textures::{self, Input, Texels, Want};
use crate::host::Background;
use crate::shaders;

pub struct Tonemap(pub(crate) Shared);

/// tonemap.wgsl's entry points, at `metered + 2 * frame` (see `setup`).
const FRAGMENT_ENTRIES: [&str; 4] = [
    "fs_tonemap",
    "fs_tonemap_metered",
    "fs_tonemap_frame",
    "fs_tonemap_frame_metered",
];
const COMPUTE_ENTRIES: [&str; 4] = [
    "cs_tonemap",
    "cs_tonemap_metered",
    "cs_tonemap_frame",
    "cs_tonemap_frame_metered",
];

/// The formats a compute tone mapper stores: rgba8unorm, holding sRGB-encoded values.
const STORED: &[TextureFormat] = &[TextureFormat::Rgba8Unorm];

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TonemapParams {
    #[serde(default)]
    pub operator: Operator,
    #[serde(default = "one")]
    pub exposure: f32,
    #[serde(default)]
    pub stage: TonemapStage,
}

/// Whether `tonemap` draws a full-screen triangle or dispatches a compute shader.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TonemapStage {
    /// Into any display format, sRGB encoded by the format where it is one.
    #[default]
    Fragment,
    /// Into an rgba8unorm storage texture, sRGB-encoded by the shader.
    Compute,
}

#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Operator {
    // The discriminants are tonemap.wgsl's OPERATOR values.
    None = 0,
    Reinhard = 1,
    #[default]
    Aces = 2,
}

impl Operator {
    /// The operator a host override names.
    pub fn from_name(name: &str) -> Option<Operator> {
        match name {
            "none" => Some(Operator::None),
            "reinhard" => Some(Operator::Reinhard),
            "aces" => Some(Operator::Aces),
            _ => None,
        }
    }
}

impl Plugin for Tonemap {
    const NAME: &'static str = "tonemap";
    type Params = TonemapParams;

    fn kind(&self, params: &TonemapParams) -> PassKind {
        match params.stage {
            TonemapStage::Fragment => PassKind::Render,
            TonemapStage::Compute => PassKind::Compute,
        }
    }

    fn setup(
        &self,
        params: TonemapParams,
        pass: &mut PassBuilder<'_>,
        slots: &mut Slots<'_>,
    ) -> Result<(), PluginError> {
        let operator = match &self.0.overrides.tonemap {
            Some(name) => Operator::from_name(name).ok_or_else(|| {
                PluginError::Invalid(format!(
                    "the tone-mapping override \"{name}\" is not none, reinhard or aces"
                ))
            })?,
            None => params.operator,
        };
        let fixed = exposure(&self.0, params.exposure)?;
        let want = Want::new("the resolved HDR input (resolve it first)", textures::HDR).samples(1);
        let (input, _) = textures::sampled(slots, pass, "hdr", want, 0)?;
        let mut inputs = vec![input];
        let metered = slots.kind("exposure").is_some();
        if metered {
            let want = Want::new("the metered exposure", textures::EXPOSURE).samples(1);
            inputs.push(textures::sampled(slots, pass, "exposure", want, 1)?.0);
        }
        let source = shaders::TONEMAP.compose(1)?.source().to_owned();
        // tonemap.wgsl's entry points, by stage: with the metered exposure or not, with
        // a host's frame exposure or not.
        let entry = usize::from(metered) + 2 * usize::from(self.0.draws_scene);
        let mut constants = vec![
            ("OPERATOR", operator as u32 as f64),
            // Under auto exposure a pass without the input is the one its file runs
            // otherwise (the frame checks that a metering pass runs): its own value.
            (
                "EXPOSURE",
                f64::from(fixed.filter(|_| !metered).unwrap_or(params.exposure)),
            ),
        ];
        constants.extend(background_constants(self.0.overrides.background));
        match params.stage {
            TonemapStage::Fragment => {
                let want = Want::new("the displayed output", textures::DISPLAY).samples(1);
                let (target, _) = textures::covered_output(slots, pass, "color", want)?;
                let entry = FRAGMENT_ENTRIES[entry];
                let draw = Fullscreen {
                    constants,
                    reads_scene: self.0.draws_scene,
                    ..Fullscreen::new("tonemap", source, entry, inputs, Some(target))
                };
                self.0.record(pass, draw);
            }
            TonemapStage::Compute => {
                let want = Want::new("the displayed output, a storage texture", STORED);
                let (target, _) =
                    textures::output(slots, pass, "color", want.samples(1), |pass, h, _| {
                        pass.storage_write(h)
                    })?;
                inputs.push(Input {
                    binding: 2,
                    texture: target,
                    aspect: Aspect::All,
                    texels: Texels::Store,
                });
                let dispatch = FullscreenCompute {
                    label: "tonemap",
                    source,
                    entry: COMPUTE_ENTRIES[entry],
                    constants,
                    inputs,
                    reads_scene: self.0.draws_scene,
                    target,
                    depth: None,
                };
                self.0.record(pass, dispatch);
            }
        }
        Ok(())
    }
}

/// tonemap.wgsl's BACKGROUND and BACKGROUND_R, _G, _B for the host's background: a
/// colour or transparency are composited here, from the background's transmittance a
/// `background` pass leaves in the HDR image's alpha (the environment is in the image
/// already).
fn background_constants(background: Option<Background>) -> Vec<(&'static str, f64)> {
    match background {
        None | Some(Background::Environment) => Vec::new(),
        Some(Background::Transparent) => vec![("BACKGROUND", 2.0)],
        Some(Background::Color(rgb)) => {
            let [r, g, b] = rgb.map(srgb_to_linear);
            vec![
                ("BACKGROUND", 1.0),
                ("BACKGROUND_R", r),
                ("BACKGROUND_G", g),
                ("BACKGROUND_B", b),
            ]
        }
    }
}

/// An sRGB byte as linear light.
fn srgb_to_linear(byte: u8) -> f64 {
    let c = f64::from(byte) / 255.0;
    match c <= 0.04045 {
        true => c / 12.92,
        false => ((c + 0.055) / 1.055).powf(2.4),
    }
}
