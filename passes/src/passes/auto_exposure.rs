//! `auto_exposure`: meters the resolved HDR image and writes the exposure that maps its
//! average luminance to a key, for `tonemap` to apply (what `--exposure auto` runs).
//!
//! ```ron
//! (name: "auto exposure", plugin: "auto_exposure",
//!  when: "auto_exposure",                   // the host's choice (analysis::Features)
//!  params: (key: 0.18, low: 0.1, high: 0.9), // these defaults
//!  inputs: { "hdr": "resolved" },           // rgba16float, 1 sample
//!  outputs: { "exposure": "exposure" })     // r32float, 1x1, storage
//! ```
//!
//! As engines meter (e.g. Unreal's histogram method): a 256-bin histogram of log2
//! luminance over the lit (non-black) pixels, the mean log2 luminance of those ranked
//! between the `low` and `high` shares, and `key / 2^mean`. Black pixels (background,
//! nothing lit) are not metered, so a small model on an empty frame is exposed for
//! itself. One workgroup meters a grid of at most about 2^18 pixels (every 2nd pixel at
//! 1280x720, every 6th at 3840x2160): one dispatch, nothing to clear between frames.
//!
//! The exposure is of this frame, for this frame (the tone mapper runs after): a
//! still image is exposed as an engine's adapted exposure converges to. An engine wanting
//! eye adaptation over time would blend with the previous frame's value here.

use serde::Deserialize;

use rgraph_core::file::{Plugin, PluginError, Slots};
use rgraph_core::shader::Stage;
use rgraph_core::{Aspect, PassBuilder, PassKind};

use crate::common::plugin::Shared;
use crate::common::textures::{self, Input, Texels, Want};
use crate::shaders;

pub struct AutoExposure(pub(crate) Shared);

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AutoExposureParams {
    /// The luminance the metered average maps to (middle grey).
    #[serde(default = "middle_grey")]
    pub key: f32,
    /// The share of the lit pixels, darkest first, left out of the average.
    #[serde(default = "low")]
    pub low: f32,
    /// The share of the lit pixels, darkest first, above which they are left out.
    #[serde(default = "high")]
    pub high: f32,
}

fn middle_grey() -> f32 {
    0.18
}
fn low() -> f32 {
    0.1
}
fn high() -> f32 {
    0.9
}

/// The metering pass as set up: what its `gpu` module records.
#[cfg_attr(not(feature = "gpu"), allow(dead_code))]
pub(crate) struct Metering {
    pub source: String,
    pub constants: Vec<(&'static str, f64)>,
    pub inputs: Vec<Input>,
}

impl Plugin for AutoExposure {
    const NAME: &'static str = "auto_exposure";
    type Params = AutoExposureParams;

    fn kind(&self, _: &AutoExposureParams) -> PassKind {
        PassKind::Compute
    }

    fn setup(
        &self,
        params: AutoExposureParams,
        pass: &mut PassBuilder<'_>,
        slots: &mut Slots<'_>,
    ) -> Result<(), PluginError> {
        if !(params.key.is_finite() && params.key > 0.0) {
            return Err(PluginError::Invalid(format!(
                "key must be finite and positive, got {}",
                params.key
            )));
        }
        if !(0.0 <= params.low && params.low < params.high && params.high <= 1.0) {
            return Err(PluginError::Invalid(format!(
                "low and high must be shares with 0 <= low < high <= 1, got low {} and high {}",
                params.low, params.high
            )));
        }
        let want = Want::new("the resolved HDR image", textures::HDR).samples(1);
        let (hdr, _) = textures::sampled(slots, pass, "hdr", want, 0)?;
        let want = Want::new("the metered exposure", textures::EXPOSURE).samples(1);
        let (exposure, _) = textures::output(slots, pass, "exposure", want, |pass, h, _| {
            pass.storage_write(h)
        })?;
        let shader = shaders::AUTO_EXPOSURE.compose(1)?;
        let Some(entry) = shader.entry("cs_auto_exposure", Stage::Compute) else {
            return Err(PluginError::Invalid(
                "auto_exposure.wgsl has no entry point cs_auto_exposure".into(),
            ));
        };
        pass.workgroup(entry.workgroup());
        let metering = Metering {
            source: shader.source().to_owned(),
            constants: vec![
                ("KEY", f64::from(params.key)),
                ("LOW", f64::from(params.low)),
                ("HIGH", f64::from(params.high)),
            ],
            inputs: vec![
                hdr,
                Input {
                    binding: 1,
                    texture: exposure,
                    aspect: Aspect::All,
                    texels: Texels::Store,
                },
            ],
        };
        self.0.record(pass, metering);
        Ok(())
    }
}

#[cfg(feature = "gpu")]
mod gpu {
    //! Recording the auto-exposure pass: one workgroup meters the image; its pipeline is made
    //! on the first frame of a device and kept.

    use super::Metering;
    use crate::common::gpu::{compute_pipeline, Compute, Frame, InputPass, Recorded, Recorder};

    impl Recorder for Metering {
        type Stage = Compute;
        type Scene = ();
        type State = InputPass<(), wgpu::ComputePipeline>;

        fn build(&self, frame: &Frame<'_, '_, Self>) -> Result<Self::State, String> {
            let (label, source) = ("auto_exposure", &self.source);
            Ok(InputPass::new(
                frame.resources,
                label,
                source,
                None,
                &self.inputs,
            ))
        }

        fn record(&self, state: &mut Self::State, frame: &mut Frame<'_, '_, Self>) -> Recorded {
            let pass = &mut *frame.pass;
            let (module, layout) = (&state.module, &state.layout);
            // The shader clears its histogram itself.
            let pipeline = state.pipelines.get((), |()| {
                compute_pipeline(
                    frame.device,
                    "auto_exposure",
                    layout,
                    module,
                    "cs_auto_exposure",
                    &self.constants,
                )
            });
            pass.set_pipeline(pipeline);
            pass.set_bind_group(1, &state.inputs.bind_group(frame.resources), &[]);
            pass.dispatch_workgroups(1, 1, 1);
            Ok(())
        }
    }
}
