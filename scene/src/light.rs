//! Punctual lights (KHR_lights_punctual) and the volumes a deferred renderer draws for them.

use glam::{DVec3, Vec3};

use super::bounds::BoundingSphere;

/// Default illuminance (lux, the unit of `intensity / distance²`) below which a light without a
/// glTF `range` is treated as contributing nothing; see [`Light::effective_range`].
pub const DEFAULT_CUTOFF_ILLUMINANCE: f32 = 0.01;

/// The most lights a scene may have, from a glTF file or `builtin:lights?count=N`: 65,536,
/// the top of the bench's lights sweep, 205 times the built-in default. Through the light
/// volumes, each light drawn as its own volume, 16,384 render at 320x180 in 12 s and 1 GB
/// on lavapipe (debug build) and 65,536 in 57 s and 2.4 GB; a hundred million aborted the
/// process.
pub const MAX_LIGHTS: u32 = 1 << 16;

/// The three KHR_lights_punctual types.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LightKind {
    /// Emits in every direction from `position`.
    Point,
    /// Cone half-angles in radians from the axis, `0 <= inner_cone < outer_cone <= π/2`: full
    /// intensity inside `inner_cone`, none outside `outer_cone`.
    Spot {
        /// Half-angle of full intensity, radians.
        inner_cone: f32,
        /// Half-angle beyond which nothing is lit, radians.
        outer_cone: f32,
    },
    /// Parallel rays along `direction`, from infinitely far (the sun).
    Directional,
}

/// A light in world space, in glTF units.
#[derive(Clone, Debug, PartialEq)]
pub struct Light {
    /// The glTF light's name, for messages.
    pub name: String,
    /// Point, spot or directional.
    pub kind: LightKind,
    /// Linear RGB.
    pub color: [f32; 3],
    /// Candela (lm/sr) for point and spot lights, lux (lm/m²) for directional lights.
    pub intensity: f32,
    /// World position (f64 like every world position); unused by directional lights.
    pub position: DVec3,
    /// Unit direction the light travels (the node's -Z); unused by point lights.
    pub direction: Vec3,
    /// glTF `range`: distance where the light's windowed falloff reaches zero; `None` = infinite.
    pub range: Option<f32>,
}

/// The geometry a deferred renderer rasterizes to find the pixels a light may reach.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LightVolume {
    /// Directional lights reach every pixel: draw a full-screen triangle.
    FullScreen,
    /// Point lights, and spot lights wider than 45° (whose cone would be wider than
    /// their range): a sphere.
    Sphere(BoundingSphere),
    /// Spot lights up to 45°: a cone with its apex at the light, `height` along `axis` to a base disc of
    /// `base_radius`. It contains the spherical sector the light reaches (`height` is the
    /// effective range, `base_radius = height * tan(outer_cone)`); a tessellated cone must
    /// circumscribe this one (scale its base by `1 / cos(π / segments)`).
    Cone {
        /// The light's position, world space.
        apex: DVec3,
        /// Unit direction from the apex to the base's center.
        axis: Vec3,
        /// Distance from the apex to the base, world units.
        height: f32,
        /// Radius of the base disc, world units.
        base_radius: f32,
    },
}

impl Light {
    /// A point light of `intensity` candela and linear RGB `color` at `position`. `range`
    /// is glTF's: where its windowed falloff reaches zero (`None`: infinite, cut off by
    /// [`Self::effective_range`]).
    pub fn point(
        name: impl Into<String>,
        position: DVec3,
        color: [f32; 3],
        intensity: f32,
        range: Option<f32>,
    ) -> Light {
        Light {
            name: name.into(),
            kind: LightKind::Point,
            color,
            intensity,
            position,
            direction: Vec3::NEG_Z,
            range,
        }
    }

    /// Whether the light adds anything: positive intensity and some positive color
    /// channel. Scene analysis counts only these, and the light passes draw only these.
    pub fn emits(&self) -> bool {
        self.intensity > 0.0 && self.color.iter().any(|&c| c > 0.0)
    }

    /// Distance beyond which a point or spot light is ignored; `None` for directional lights.
    ///
    /// Without falloff windowing, illuminance at distance `d` is `intensity * max(color) / d²`;
    /// it drops below `cutoff` (lux, see [`DEFAULT_CUTOFF_ILLUMINANCE`]) at
    /// `d = sqrt(intensity * max(color) / cutoff)`. With a glTF `range` the light is zero beyond
    /// it anyway, so the result is the smaller of the two. A light with zero intensity or color
    /// has range 0.
    pub fn effective_range(&self, cutoff: f32) -> Option<f32> {
        (self.kind != LightKind::Directional).then(|| self.local_range(cutoff))
    }

    /// The sphere this crate puts around the lit region: centered on a point light with radius
    /// [`Self::effective_range`] `r`; for a spot light of outer half-angle θ, the sphere through
    /// the apex and the rim of the cone's cap when θ ≤ 45° (center `r / (2 cos θ)` along the
    /// axis, radius the same), else the sphere around the rim's disc (center `r cos θ` along the
    /// axis, radius `r sin θ`); both contain the whole spherical sector. `None` for directional
    /// lights. Meant for culling and light clustering.
    pub fn bounding_sphere(&self, cutoff: f32) -> Option<BoundingSphere> {
        let range = f64::from(self.local_range(cutoff));
        match self.kind {
            LightKind::Directional => None,
            LightKind::Point => Some(BoundingSphere {
                center: self.position,
                radius: range,
            }),
            LightKind::Spot { outer_cone, .. } => Some(self.sector_sphere(range, outer_cone)),
        }
    }

    /// [`Self::bounding_sphere`] of a spot light's sector of `range` and outer half-angle
    /// `outer_cone`.
    fn sector_sphere(&self, range: f64, outer_cone: f32) -> BoundingSphere {
        let theta = f64::from(outer_cone);
        let (offset, radius) = if theta <= std::f64::consts::FRAC_PI_4 {
            let t = range / (2.0 * theta.cos());
            (t, t)
        } else {
            (range * theta.cos(), range * theta.sin())
        };
        BoundingSphere {
            center: self.position + self.direction.as_dvec3() * offset,
            radius,
        }
    }

    /// The light volume to rasterize; see [`LightVolume`].
    pub fn volume(&self, cutoff: f32) -> LightVolume {
        let range = self.local_range(cutoff);
        match self.kind {
            LightKind::Directional => LightVolume::FullScreen,
            LightKind::Point => LightVolume::Sphere(BoundingSphere {
                center: self.position,
                radius: f64::from(range),
            }),
            // Wider than 45°, the cone's base outgrows the range (at 90° tan overflows
            // f32 to a mesh 1e8 wide): the bounding sphere is the tighter volume.
            LightKind::Spot { outer_cone, .. } if outer_cone > std::f32::consts::FRAC_PI_4 => {
                LightVolume::Sphere(self.sector_sphere(f64::from(range), outer_cone))
            }
            LightKind::Spot { outer_cone, .. } => LightVolume::Cone {
                apex: self.position,
                axis: self.direction,
                height: range,
                base_radius: range * outer_cone.tan(),
            },
        }
    }

    /// [`Self::effective_range`]'s formula, whatever the kind.
    fn local_range(&self, cutoff: f32) -> f32 {
        let brightest = self.color.into_iter().fold(0.0f32, f32::max);
        // In f64: `intensity * brightest / cutoff` overflows f32 from an intensity of about
        // 3.4e36 (at the default cutoff), and an infinite range gave an empty frame. Its
        // square root is clamped to f32's range, which only a cutoff below 1e-7 needs.
        let illuminance = f64::from(self.intensity.max(0.0)) * f64::from(brightest);
        let cutoff_radius = (illuminance / f64::from(cutoff))
            .sqrt()
            .min(f64::from(f32::MAX)) as f32;
        self.range.map_or(cutoff_radius, |r| r.min(cutoff_radius))
    }
}
