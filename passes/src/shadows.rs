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
    /// hardware comparison sampler's bilinear 2 x 2 comparison, averaged (a 4 x 4 texel
    /// footprint with tent-like weights).
    #[default]
    Pcf,
}

impl ShadowFilter {
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
    /// The most lights given shadow maps each frame: the lights covering most of the
    /// screen (a directional light covers all of it), as many as fit the atlas's
    /// [`SHADOW_VIEWS`] maps (a directional light takes [`CASCADES`], a point light
    /// [`POINT_FACES`], a spot light one).
    pub lights: u32,
}

/// Shadow maps the atlas holds: a grid of [`ATLAS_GRID`] x [`ATLAS_GRID`] equal tiles,
/// each one view's map.
pub const SHADOW_VIEWS: u32 = ATLAS_GRID * ATLAS_GRID;
/// Tiles per side of the shadow atlas.
pub const ATLAS_GRID: u32 = 4;
/// Cascades per directional light (Dimitrov's cascaded shadow maps, NVIDIA 2007).
pub const CASCADES: u32 = 4;
/// Maps per point light: a cube's six faces, each a tile of the atlas.
pub const POINT_FACES: u32 = 6;
/// The default of [`Shadows::lights`]: the sun and three spot lights, whose maps fill
/// the 4 x 4 atlas at most (a directional light takes [`CASCADES`] tiles, a point light
/// [`POINT_FACES`], so a sun and two point lights fill it).
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
    /// More shadowed lights than the atlas has maps.
    #[error(
        "{0} shadowed lights is out of range: the shadow atlas holds {SHADOW_VIEWS} maps, so \
         at most {SHADOW_VIEWS} lights cast shadows (0: none does)"
    )]
    TooManyLights(u32),
}

impl Shadows {
    /// Settings with `filter` and at most `lights` shadowed lights, checked.
    pub fn new(filter: ShadowFilter, lights: u32) -> Result<Shadows, ShadowsError> {
        match lights <= SHADOW_VIEWS {
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
