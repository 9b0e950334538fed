//! `fxaa`: FXAA 3.11 (Lottes 2011, the PC quality variant), a post filter on the
//! tone-mapped image: what many users choose instead of MSAA, and what the NVIDIA
//! deferred-MSAA sample (seed 002) toggles on top of it.
//!
//! ```ron
//! (name: "fxaa", plugin: "fxaa",
//!  params: (preset: 12, subpix: 0.75, edge_threshold: 0.166, edge_threshold_min: 0.0833),
//!  inputs: { "ldr": "ldr" },       // rgba8unorm-srgb or rgba8unorm, 1 sample: tone mapped
//!  outputs: { "color": "color" })  // the same formats, 1 sample
//! ```
//!
//! The parameters are Fxaa3_11.h's, with its defaults: `preset` is `FXAA_QUALITY__PRESET`
//! (10 to 15: fewer, coarser search steps, the fastest; 20 to 29: more steps; 39: the
//! finest, "extreme quality"), which sets how far and how finely the filter searches
//! along an edge for its ends; `subpix` (0 to 1) how much sub-pixel aliasing it removes
//! (more softens more); `edge_threshold` (1/16 to 1/2) and `edge_threshold_min` (0 to
//! 1/8) the relative and absolute contrast below which a pixel is left alone. Anything
//! else is an error naming the parameter and its valid range.
//!
//! FXAA needs perceptual (gamma-space) luma and an image in display range, so it runs
//! after tone mapping; it sees only the final colors, so it smooths edges no matter what
//! made them (geometry, shading, textures) and, unlike MSAA, cannot recover detail
//! smaller than a pixel.

use serde::Deserialize;

use rgraph_core::file::{Plugin, PluginError, Slots};
use rgraph_core::{PassBuilder, PassKind};

use crate::common::fullscreen::Fullscreen;
use crate::common::plugin::Shared;
use crate::common::textures::{self, Texels, Want};
use crate::shaders;

pub struct Fxaa(pub(crate) Shared);

#[derive(Clone, Debug, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct FxaaParams {
    /// `FXAA_QUALITY__PRESET`: 10 to 15, 20 to 29 or 39.
    pub preset: u32,
    /// `fxaaQualitySubpix`, in [0, 1].
    pub subpix: f32,
    /// `fxaaQualityEdgeThreshold`, in [1/16, 1/2].
    pub edge_threshold: f32,
    /// `fxaaQualityEdgeThresholdMin`, in [0, 1/8].
    pub edge_threshold_min: f32,
}

/// Fxaa3_11.h's defaults.
impl Default for FxaaParams {
    fn default() -> FxaaParams {
        FxaaParams {
            preset: 12,
            subpix: 0.75,
            edge_threshold: 0.166,
            edge_threshold_min: 0.0833,
        }
    }
}

/// Fxaa3_11.h's quality presets: `FXAA_QUALITY__P0..` (the distances, in texels, of
/// each search step along an edge; the first is where the search starts), by preset.
const PRESETS: [(u32, &[f32]); 17] = [
    (10, &[1.5, 3.0, 12.0]),
    (11, &[1.0, 1.5, 3.0, 12.0]),
    (12, &[1.0, 1.5, 2.0, 4.0, 12.0]),
    (13, &[1.0, 1.5, 2.0, 2.0, 4.0, 12.0]),
    (14, &[1.0, 1.5, 2.0, 2.0, 2.0, 4.0, 12.0]),
    (15, &[1.0, 1.5, 2.0, 2.0, 2.0, 2.0, 4.0, 12.0]),
    (20, &[1.5, 2.0, 8.0]),
    (21, &[1.0, 1.5, 2.0, 8.0]),
    (22, &[1.0, 1.5, 2.0, 2.0, 8.0]),
    (23, &[1.0, 1.5, 2.0, 2.0, 2.0, 8.0]),
    (24, &[1.0, 1.5, 2.0, 2.0, 2.0, 3.0, 8.0]),
    (25, &[1.0, 1.5, 2.0, 2.0, 2.0, 2.0, 4.0, 8.0]),
    (26, &[1.0, 1.5, 2.0, 2.0, 2.0, 2.0, 2.0, 4.0, 8.0]),
    (27, &[1.0, 1.5, 2.0, 2.0, 2.0, 2.0, 2.0, 2.0, 4.0, 8.0]),
    (28, &[1.0, 1.5, 2.0, 2.0, 2.0, 2.0, 2.0, 2.0, 2.0, 4.0, 8.0]),
    (
        29,
        &[1.0, 1.5, 2.0, 2.0, 2.0, 2.0, 2.0, 2.0, 2.0, 2.0, 4.0, 8.0],
    ),
    (
        39,
        &[1.0, 1.0, 1.0, 1.0, 1.0, 1.5, 2.0, 2.0, 2.0, 2.0, 4.0, 8.0],
    ),
];

impl FxaaParams {
    /// The search steps of the preset, after checking every parameter.
    fn steps(&self) -> Result<&'static [f32], PluginError> {
        let in_range = |name: &str, value: f32, low: f32, high: f32| {
            if (low..=high).contains(&value) {
                Ok(())
            } else {
                Err(PluginError::Invalid(format!(
                    "FXAA's {name} is {value}, but must be between {low} and {high}"
                )))
            }
        };
        in_range("subpix", self.subpix, 0.0, 1.0)?;
        in_range("edge_threshold", self.edge_threshold, 0.0625, 0.5)?;
        in_range("edge_threshold_min", self.edge_threshold_min, 0.0, 0.125)?;
        PRESETS
            .iter()
            .find(|(preset, _)| *preset == self.preset)
            .map(|(_, steps)| *steps)
            .ok_or_else(|| {
                PluginError::Invalid(format!(
                    "FXAA quality preset {} does not exist: FXAA 3.11 has presets 10 to 15 \
                     (fastest), 20 to 29 and 39 (finest)",
                    self.preset
                ))
            })
    }
}

/// The WGSL block fxaa.wgsl's search loop reads: the preset's steps.
fn steps_wgsl(steps: &[f32]) -> String {
    let list: Vec<String> = steps.iter().map(|s| format!("{s:?}")).collect();
    format!(
        "// Generated: the quality preset's search steps.\n\
         const FXAA_STEP_COUNT: u32 = {n}u;\n\
         const FXAA_STEPS = array<f32, {n}>({});\n",
        list.join(", "),
        n = steps.len()
    )
}

impl Plugin for Fxaa {
    const NAME: &'static str = "fxaa";
    type Params = FxaaParams;

    fn kind(&self, _: &FxaaParams) -> PassKind {
        PassKind::Render
    }

    fn setup(
        &self,
        params: FxaaParams,
        pass: &mut PassBuilder<'_>,
        slots: &mut Slots<'_>,
    ) -> Result<(), PluginError> {
        let steps = params.steps()?;
        let want = Want::new("the tone-mapped image FXAA filters", textures::DISPLAY).samples(1);
        let (mut input, desc) = textures::sampled(slots, pass, "ldr", want, 0)?;
        // The shader's luma depends on whether reads decode sRGB, fixed at setup: every
        // format the device may give the texture must agree.
        // Where the pass's condition picks a conditional format, that one decides.
        let formats = desc.formats_where(pass.condition());
        let linear = formats
            .first()
            .map_or(desc.format.is_srgb(), |f| f.is_srgb());
        if formats.iter().any(|f| f.is_srgb() != linear) {
            return Err(PluginError::Slot {
                slot: "ldr".to_owned(),
                resource: slots.resource("ldr").unwrap_or("ldr").to_owned(),
                why: "may be sRGB or not, depending on the device: FXAA needs to know which"
                    .to_owned(),
            });
        }
        input.texels = Texels::Filtered { sampler: 1 };
        let want = Want::new("the anti-aliased output", textures::DISPLAY).samples(1);
        let (target, _) = textures::covered_output(slots, pass, "color", want)?;
        let source = shaders::FXAA
            .compose_with(1, &steps_wgsl(steps))?
            .source()
            .to_owned();
        let draw = Fullscreen {
            constants: vec![
                ("LINEAR_INPUT", f64::from(u8::from(linear))),
                ("SUBPIX", f64::from(params.subpix)),
                ("EDGE_THRESHOLD", f64::from(params.edge_threshold)),
                ("EDGE_THRESHOLD_MIN", f64::from(params.edge_threshold_min)),
            ],
            ..Fullscreen::new("fxaa", source, "fs_fxaa", vec![input], Some(target))
        };
        self.0.record(pass, draw);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_preset_is_known_and_others_are_refused() {
        for (preset, steps) in PRESETS {
            let params = FxaaParams {
                preset,
                ..FxaaParams::default()
            };
            assert_eq!(params.steps().unwrap(), steps);
        }
        let message = |params: FxaaParams| params.steps().unwrap_err().to_string();
        let preset = message(FxaaParams {
            preset: 16,
            ..FxaaParams::default()
        });
        assert!(preset.contains("preset 16 does not exist"), "{preset}");
        let subpix = message(FxaaParams {
            subpix: f32::NAN,
            ..FxaaParams::default()
        });
        assert!(subpix.contains("subpix is NaN"), "{subpix}");
    }
}
