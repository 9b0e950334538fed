//! `tonemap`: exposure and a tone-mapping operator from the resolved HDR target into the
//! displayable output.
//!
//! ```ron
//! (name: "tonemap", plugin: "tonemap",
//!  params: (operator: aces, exposure: 1.0),   // these defaults; or none | reinhard
//!  inputs: { "hdr": "resolved" },              // rgba16float, 1 sample
//!  outputs: { "color": "color" })              // rgba8unorm-srgb (or rgba8unorm), 1 sample
//! ```
//!
//! With an `"exposure"` input (the 1x1 r32float texture `auto_exposure` writes), the pass
//! multiplies the metered exposure by `exposure` (then a compensation): what the host's
//! auto exposure runs, under the condition `auto_exposure`.
//!
//! `none` clamps the exposed linear color to [0, 1]; `reinhard` is `c / (1 + c)` per
//! channel; `aces` is Narkowicz's fit of the ACES filmic curve. An sRGB output encodes
//! the result. The host's overrides replace `operator` and `exposure` when set. With a
//! host, the frame's exposure factor (`FrameInputs::exposure`, from the scene's light
//! info, group 0) multiplies the result each frame: a uniform, not the pipeline constant
//! `exposure` becomes, so a new value every frame builds no pipeline.

use serde::Deserialize;

use graph_core::file::{Plugin, PluginError, Slots};
use graph_core::{PassBuilder, PassKind};

use super::resolve::{exposure, one};
use crate::common::fullscreen::Fullscreen;
use crate::common::plugin::Shared;
use crate::common::textures::{self, Want};
use crate::shaders;

pub struct Tonemap(pub(crate) Shared);

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TonemapParams {
    #[serde(default)]
    pub operator: Operator,
    #[serde(default = "one")]
    pub exposure: f32,
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

    fn kind(&self, _: &TonemapParams) -> PassKind {
        PassKind::Render
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
        let want = Want::new("the displayed output", textures::DISPLAY).samples(1);
        let (target, _) = textures::color_output(slots, pass, "color", want, [0.0; 4])?;
        let draw = Fullscreen {
            label: "tonemap",
            source: shaders::TONEMAP.compose(1)?.source().to_owned(),
            entry: match (metered, self.0.draws_scene) {
                (true, true) => "fs_tonemap_frame_metered",
                (false, true) => "fs_tonemap_frame",
                (true, false) => "fs_tonemap_metered",
                (false, false) => "fs_tonemap",
            },
            constants: vec![
                ("OPERATOR", operator as u32 as f64),
                // Under auto exposure a pass without the input is the one its file runs
                // otherwise (the frame checks that a metering pass runs): its own value.
                (
                    "EXPOSURE",
                    f64::from(fixed.filter(|_| !metered).unwrap_or(params.exposure)),
                ),
            ],
            inputs,
            reads_scene: self.0.draws_scene,
            target: Some(target),
            stencil_mark: None,
            blend: None,
        };
        self.0.record(pass, draw);
        Ok(())
    }
}
