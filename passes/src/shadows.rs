//! Which lights cast shadows and how their shadow maps are filtered: the host's choice
//! ([`Overrides::shadows`](crate::Overrides::shadows), `rgraph render --shadows` and
//! `--shadowed-lights`), and the atlas layout the `shadow_maps` pass and the light
//! passes share (docs/design/shadows.md).

use thiserror::Error;

/// How a shadowed light's visibility is read from its shadow map.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub enum ShadowFilter {
    /// No light casts a shadow: the shadow pass is culled (the scene's `shadows` feature
    /// is unset) and the light passes are the unshadowed ones.
    Off,
    /// One depth comparison at the nearest texel: hard, aliased edges.
    Hard,
    /// Percentage-closer filtering: a 3 x 3 grid of taps one texel apart, each a
    /// bilinear 2 x 2 comparison, averaged (a 4 x 4 texel footprint with tent-like
    /// weights), summed texel by texel in the shader (shadow.wgsl), which reads an atlas
    /// of either format.
    #[default]
    Pcf,
}

impl ShadowFilter {
    /// Every filter, as the command line names them.
    pub const ALL: [ShadowFilter; 3] = [ShadowFilter::Off, ShadowFilter::Hard, ShadowFilter::Pcf];

    /// Its name on the command line and in results.
    pub fn name(self) -> &'static str {
        match self {
            ShadowFilter::Off => "off",
            ShadowFilter::Hard => "hard",
            ShadowFilter::Pcf => "pcf",
        }
    }

    /// shadow.wgsl's `SHADOW_FILTER`.
    pub(crate) fn constant(self) -> u32 {
        match self {
            ShadowFilter::Off | ShadowFilter::Hard => 0,
            ShadowFilter::Pcf => 1,
        }
    }
}

/// The shadow settings of one host.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct Shadows {
    /// How the maps are read, or no shadows at all.
    pub filter: ShadowFilter,
    /// The most lights given shadow maps each frame, at most [`MAX_SHADOWED_LIGHTS`]: the
    /// lights covering most of the screen (a directional light covers all of it), as
    /// many as fit the atlas (a directional light takes [`CASCADES`] maps, a point light
    /// [`POINT_FACES`], a spot light one, each from a quarter of the atlas's side down
    /// to 1/[`ATLAS_UNITS`] of it).
    pub lights: u32,
}

/// The atlas's side in units of the smallest map's: a map is a square of 8, 4, 2 or 1
/// units (in a 4096-texel atlas, 1024, 512, 256 or 128 texels), placed on the units'
/// grid.
pub const ATLAS_UNITS: u32 = 32;
/// The most maps (views) one frame's atlas holds: 64 point lights' faces fit.
pub const SHADOW_VIEWS: u32 = 512;
/// The most lights `--shadowed-lights` may ask for.
pub const MAX_SHADOWED_LIGHTS: u32 = 64;
/// Cascades per directional light (Dimitrov's cascaded shadow maps, NVIDIA 2007).
pub const CASCADES: u32 = 4;
/// Maps per point light: a cube's six faces, each a map of the atlas.
pub const POINT_FACES: u32 = 6;
/// The default of [`Shadows::lights`]: the sun and three more.
pub const DEFAULT_SHADOWED_LIGHTS: u32 = 4;

impl Default for Shadows {
    fn default() -> Shadows {
        Shadows {
            filter: ShadowFilter::Pcf,
            lights: DEFAULT_SHADOWED_LIGHTS,
        }
    }
}

/// A shadow setting out of range.
#[derive(Debug, Error, PartialEq, Eq)]
pub enum ShadowsError {
    /// More shadowed lights than the atlas may hold.
    #[error(
        "{0} shadowed lights is out of range: at most {MAX_SHADOWED_LIGHTS} lights cast \
         shadows (0: none does)"
    )]
    TooManyLights(u32),
}

impl Shadows {
    /// Settings with `filter` and at most `lights` shadowed lights, checked.
    pub fn new(filter: ShadowFilter, lights: u32) -> Result<Shadows, ShadowsError> {
        match lights <= MAX_SHADOWED_LIGHTS {
            true => Ok(Shadows { filter, lights }),
            false => Err(ShadowsError::TooManyLights(lights)),
        }
    }

    /// Whether any light may cast a shadow: the host unsets the scene's `shadows`
    /// feature otherwise.
    pub fn enabled(self) -> bool {
        self.filter != ShadowFilter::Off && self.lights > 0
    }
}
