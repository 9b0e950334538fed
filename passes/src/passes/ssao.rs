//! `ssao` and `ssao_blur`: screen-space ambient occlusion on the multisampled G-buffer
//! (GTAO, Jimenez et al. 2016, at full or half resolution), then a bilateral blur; the light
//! passes take the result as their optional `ao` input (common/ao.rs) and darken only
//! the ambient and environment light with it, as seed 004 argues: occlusion of light
//! from everywhere, not a shadow of the direct lights.
//!
//! ```ron
//! (name: "ssao", plugin: "ssao",
//!  params: (radius: 0.5, directions: 4, steps: 4, bias: 0.05),   // these defaults
//!  inputs: { "normal": "normal", "view_depth": "view_depth" },   // the G-buffer's, any samples
//!  outputs: { "ao": "ao_raw" })     // r8unorm, 1 sample; the G-buffer's size or half
//! (name: "ssao blur", plugin: "ssao_blur",
//!  params: (depth_tolerance: 0.05),                                // the default
//!  inputs: { "raw": "ao_raw", "view_depth": "view_depth" },
//!  outputs: { "ao": "ao" })        // r8unorm; or "color" (rgba8unorm[-srgb]): the debug view
//! ```
//!
//! `ssao` searches `directions` slices through the view ray (rotated per pixel in a 4 x 4
//! pattern), each both ways with `steps` depth samples out to `radius` world units, for
//! the horizon that occluders within the radius raise above the tangent plane (by more
//! than the elevation whose sine is `bias`), and integrates the cosine-weighted visible
//! arc between the horizons (GTAO's equation 10). Each pixel's sum is divided by the same
//! slices' sum without occluders, so a surface with nothing above it within the radius
//! is exactly 1 however it is tilted, and occlusion only ever darkens (1 is stored as
//! 255, which the light passes multiply by exactly 1.0). `ssao_blur` averages the 4 x 4
//! window the rotations repeat over, each neighbour weighted down to 0 as its view depth
//! departs from the pixel's by `depth_tolerance` of it, so occlusion stays on its own
//! side of a silhouette. With a `color` output instead of `ao` it writes the blurred AO
//! as grey: the debug view of the AO term.
//!
//! The resolution follows the raw AO texture's size: the G-buffer's, or half of it
//! (`size: Relative(0.5)` where the G-buffer is `Relative(1.0)`), where `ssao` works on
//! each 2 x 2 block's top-left pixel (a quarter of the work) and the blur, at the
//! G-buffer's size, upsamples with the same depth weights. Other sizes are errors naming
//! the slot.
//!
//! Which depth of a multisampled pixel: sample 0's. The per-pixel light pass shades
//! non-edge pixels from sample 0, so there the occlusion belongs to exactly the surface
//! it darkens (a min or max of the samples would too, since all samples agree there).
//! On edge pixels the samples hold two surfaces and one AO value serves all of them:
//! sample 0 at least pairs the depth with sample 0's own normal, which a min or max
//! depth would mix with another surface's, and the blur's depth weights keep either
//! surface's occlusion from spreading across the silhouette.
//!
//! Bad parameters (a radius that is not finite and positive, no directions or steps or
//! more than 16 and 32, a bias outside [0, 1), a tolerance that is not positive) are
//! errors naming the parameter.

use serde::Deserialize;

use rgraph_core::file::{Plugin, PluginError, Slots};
use rgraph_core::{PassBuilder, PassKind, Size, TextureDesc};

use crate::common::ao::AO;
use crate::common::fullscreen::Fullscreen;
use crate::common::plugin::Shared;
use crate::common::textures::{self, Want};
use crate::shaders;

pub struct Ssao(pub(crate) Shared);
pub struct SsaoBlur(pub(crate) Shared);

#[derive(Clone, Debug, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SsaoParams {
    /// World units: occluders farther from the shaded point do not count.
    pub radius: f32,
    /// Slices through the view ray per pixel, 1 to 16.
    pub directions: u32,
    /// Depth samples on each side of a slice, 1 to 32.
    pub steps: u32,
    /// The sine of the elevation above the tangent plane an occluder needs, in [0, 1).
    pub bias: f32,
}

impl Default for SsaoParams {
    fn default() -> SsaoParams {
        SsaoParams {
            radius: 0.5,
            directions: 4,
            steps: 4,
            bias: 0.05,
        }
    }
}

#[derive(Clone, Debug, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SsaoBlurParams {
    /// The relative view-depth difference at which a neighbour stops counting.
    pub depth_tolerance: f32,
}

impl Default for SsaoBlurParams {
    fn default() -> SsaoBlurParams {
        SsaoBlurParams {
            depth_tolerance: 0.05,
        }
    }
}

impl SsaoParams {
    fn check(&self) -> Result<(), PluginError> {
        let invalid = |what: String| Err(PluginError::Invalid(format!("SSAO's {what}")));
        if !(self.radius.is_finite() && self.radius > 0.0) {
            return invalid(format!(
                "radius is {}, but must be finite and positive (world units)",
                self.radius
            ));
        }
        if !(1..=16).contains(&self.directions) {
            return invalid(format!(
                "directions is {}, but must be from 1 to 16",
                self.directions
            ));
        }
        if !(1..=32).contains(&self.steps) {
            return invalid(format!("steps is {}, but must be from 1 to 32", self.steps));
        }
        if !(0.0..1.0).contains(&self.bias) {
            return invalid(format!(
                "bias is {}, but must be at least 0 and below 1",
                self.bias
            ));
        }
        Ok(())
    }
}

/// The G-buffer's view depth, bound at 1, and its description.
fn view_depth(
    slots: &mut Slots<'_>,
    pass: &mut PassBuilder<'_>,
) -> Result<(textures::Input, TextureDesc), PluginError> {
    let want = Want::new("the G-buffer's view depth", textures::VIEW_DEPTH);
    textures::sampled(slots, pass, "view_depth", want, 1)
}

/// G-buffer pixels per side of a texel of `slot`'s texture (`ao`): 1 at the G-buffer's
/// size, 2 at half of it (fs_gtao then works on each 2 x 2 block's top-left pixel, and
/// fs_blur upsamples); `allow_half` false admits 1 only.
fn texel_scale(
    slots: &Slots<'_>,
    slot: &str,
    gbuffer: Size,
    ao: Size,
    allow_half: bool,
) -> Result<i32, PluginError> {
    let half = match (gbuffer, ao) {
        (g, a) if g == a => return Ok(1),
        (Size::Relative(g), Size::Relative(a)) => a * 2.0 == g,
        (Size::Absolute(gw, gh), Size::Absolute(aw, ah)) => (aw * 2, ah * 2) == (gw, gh),
        _ => false,
    };
    match (half, allow_half) {
        (true, true) => Ok(2),
        _ => Err(PluginError::Slot {
            slot: slot.to_owned(),
            resource: slots.resource(slot).unwrap_or(slot).to_owned(),
            why: format!(
                "is {ao:?}, but must be the G-buffer's size ({gbuffer:?}){}",
                if allow_half { " or half of it" } else { "" }
            ),
        }),
    }
}

impl Plugin for Ssao {
    const NAME: &'static str = "ssao";
    type Params = SsaoParams;

    fn kind(&self, _: &SsaoParams) -> PassKind {
        PassKind::Render
    }

    fn setup(
        &self,
        params: SsaoParams,
        pass: &mut PassBuilder<'_>,
        slots: &mut Slots<'_>,
    ) -> Result<(), PluginError> {
        params.check()?;
        let (depth, gbuffer) = view_depth(slots, pass)?;
        let samples = gbuffer.samples;
        let want = Want::new("the G-buffer's normals", textures::NORMAL).samples(samples);
        let (normal, _) = textures::sampled(slots, pass, "normal", want, 0)?;
        let want = Want::new("the ambient occlusion", AO).samples(1);
        let (target, ao) = textures::covered_output(slots, pass, "ao", want)?;
        let scale = texel_scale(slots, "ao", gbuffer.size, ao.size, true)?;
        let source = shaders::SSAO.compose(samples)?.source().to_owned();
        let draw = Fullscreen {
            constants: vec![
                ("RADIUS", f64::from(params.radius)),
                ("DIRECTIONS", f64::from(params.directions)),
                ("STEPS", f64::from(params.steps)),
                ("BIAS", f64::from(params.bias)),
                ("SCALE", f64::from(scale)),
            ],
            reads_scene: true,
            ..Fullscreen::new("ssao", source, "fs_gtao", vec![normal, depth], Some(target))
        };
        self.0.record(pass, draw);
        Ok(())
    }
}

impl Plugin for SsaoBlur {
    const NAME: &'static str = "ssao_blur";
    type Params = SsaoBlurParams;

    fn kind(&self, _: &SsaoBlurParams) -> PassKind {
        PassKind::Render
    }

    fn setup(
        &self,
        params: SsaoBlurParams,
        pass: &mut PassBuilder<'_>,
        slots: &mut Slots<'_>,
    ) -> Result<(), PluginError> {
        let tolerance = params.depth_tolerance;
        if !(tolerance.is_finite() && tolerance > 0.0) {
            return Err(PluginError::Invalid(format!(
                "SSAO blur's depth_tolerance is {tolerance}, but must be finite and positive"
            )));
        }
        let (depth, gbuffer) = view_depth(slots, pass)?;
        let samples = gbuffer.samples;
        let want = Want::new("the unblurred ambient occlusion", AO).samples(1);
        let (raw, raw_desc) = textures::sampled(slots, pass, "raw", want, 2)?;
        let scale = texel_scale(slots, "raw", gbuffer.size, raw_desc.size, true)?;
        // The AO for the light passes, or the debug view of it.
        let (slot, want) = match slots.is_output("color") {
            true => ("color", Want::new("the AO debug view", textures::DISPLAY)),
            false => ("ao", Want::new("the ambient occlusion", AO)),
        };
        let (target, out) = textures::covered_output(slots, pass, slot, want.samples(1))?;
        texel_scale(slots, slot, gbuffer.size, out.size, false)?;
        let source = shaders::SSAO.compose(samples)?.source().to_owned();
        let draw = Fullscreen {
            constants: vec![
                ("BLUR_DEPTH", f64::from(tolerance)),
                ("SCALE", f64::from(scale)),
            ],
            ..Fullscreen::new(
                "ssao_blur",
                source,
                "fs_blur",
                vec![raw, depth],
                Some(target),
            )
        };
        self.0.record(pass, draw);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bad_ssao_parameters_are_refused_by_name() {
        let message = |params: SsaoParams| params.check().unwrap_err().to_string();
        let radius = message(SsaoParams {
            radius: -1.0,
            ..SsaoParams::default()
        });
        assert!(radius.contains("SSAO's radius is -1"), "{radius}");
        let directions = message(SsaoParams {
            directions: 0,
            ..SsaoParams::default()
        });
        assert!(directions.contains("directions is 0"), "{directions}");
        let steps = message(SsaoParams {
            steps: 33,
            ..SsaoParams::default()
        });
        assert!(steps.contains("steps is 33"), "{steps}");
        assert!(SsaoParams::default().check().is_ok());
    }
}
