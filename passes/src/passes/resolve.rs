//! `resolve`: averages the samples of the multisampled HDR target into a single-sampled
//! one, after all lighting (resolving the G-buffer instead would be wrong, seed 000).
//!
//! ```ron
//! (name: "resolve", plugin: "resolve",
//!  params: (mode: box, exposure: 1.0),   // these defaults; or mode: tonemapped
//!  inputs: { "hdr": "hdr_lit" },          // rgba16float, any sample count
//!  outputs: { "resolved": "resolved" })   // rgba16float, 1 sample
//! ```
//!
//! `box` is the plain average. `tonemapped` weights each sample by
//! `1 / (1 + exposure * luminance)`: the average of Reinhard-tonemapped samples with the
//! tone mapping undone, so one very bright sample does not wash out an anti-aliased edge.
//! `exposure` should be the tone mapper's; the host's exposure override replaces it.
//! Samples are clamped to [0, half-float max] first, so the output is always finite.

use serde::Deserialize;

use rgraph_core::file::{Plugin, PluginError, Slots};
use rgraph_core::{PassBuilder, PassKind};

use crate::common::fullscreen::Fullscreen;
use crate::common::plugin::Shared;
use crate::common::textures::{self, Want};
use crate::host::Exposure;
use crate::shaders;

pub struct Resolve(pub(crate) Shared);

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ResolveParams {
    #[serde(default)]
    pub mode: ResolveMode,
    #[serde(default = "one")]
    pub exposure: f32,
}

#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ResolveMode {
    #[default]
    Box,
    Tonemapped,
}

pub(crate) fn one() -> f32 {
    1.0
}

/// The fixed exposure to use: the host's override, else `param`; finite and positive.
/// `None` when the host asks for auto exposure.
pub(crate) fn exposure(shared: &Shared, param: f32) -> Result<Option<f32>, PluginError> {
    let exposure = match shared.overrides.exposure {
        Some(Exposure::Auto) => return Ok(None),
        Some(Exposure::Fixed(exposure)) => exposure,
        None => param,
    };
    if exposure.is_finite() && exposure > 0.0 {
        Ok(Some(exposure))
    } else {
        Err(PluginError::Invalid(format!(
            "exposure must be finite and positive, got {exposure}"
        )))
    }
}

/// The exposure a resolve applies: only a tone-mapped resolve uses it, and auto exposure
/// cannot serve one, since the frame is metered after its resolve.
pub(crate) fn resolve_exposure(
    shared: &Shared,
    param: f32,
    mode: ResolveMode,
) -> Result<f32, PluginError> {
    match (exposure(shared, param)?, mode) {
        (Some(exposure), _) => Ok(exposure),
        (None, ResolveMode::Box) => Ok(1.0),
        (None, ResolveMode::Tonemapped) => Err(PluginError::Invalid(
            "auto exposure meters the resolved image, but `resolve: tonemapped` applies \
             exposure before resolving: give a fixed exposure, or use a pipeline that \
             resolves with `box` and tone maps after"
                .into(),
        )),
    }
}

impl Plugin for Resolve {
    const NAME: &'static str = "resolve";
    type Params = ResolveParams;

    fn kind(&self, _: &ResolveParams) -> PassKind {
        PassKind::Render
    }

    fn setup(
        &self,
        params: ResolveParams,
        pass: &mut PassBuilder<'_>,
        slots: &mut Slots<'_>,
    ) -> Result<(), PluginError> {
        let exposure = resolve_exposure(&self.0, params.exposure, params.mode)?;
        let want = Want::new("the lit HDR target", textures::HDR);
        let (input, desc) = textures::sampled(slots, pass, "hdr", want, 0)?;
        let want = Want::new("the resolved HDR target", textures::HDR).samples(1);
        let (target, _) = textures::covered_output(slots, pass, "resolved", want)?;
        let mode = match params.mode {
            ResolveMode::Box => 0.0,
            ResolveMode::Tonemapped => 1.0,
        };
        let source = shaders::RESOLVE.compose(desc.samples)?.source().to_owned();
        let draw = Fullscreen {
            constants: vec![("MODE", mode), ("EXPOSURE", f64::from(exposure))],
            ..Fullscreen::new("resolve", source, "fs_resolve", vec![input], Some(target))
        };
        self.0.record(pass, draw);
        Ok(())
    }
}
