//! KHR_lights_punctual lights to [`Light`]s.

use std::f32::consts::FRAC_PI_2;
use std::path::Path;

use glam::{DMat4, DVec3};
use gltf::khr_lights_punctual::Kind;

use crate::error::label;
use crate::{Light, LightKind, SceneError};

/// Converts a light placed at `world`: position from the translation, direction from the
/// node's -Z axis. Rejects values the extension forbids (negative intensity or color, range <= 0, cone
/// angles outside `0 <= inner <= outer <= π/2`), which would break light volumes, and values
/// beyond f32's range (`1e39` in the file), which would light the frame with infinities.
pub(super) fn convert(
    file: &Path,
    light: &gltf::khr_lights_punctual::Light,
    world: &DMat4,
) -> Result<Light, SceneError> {
    let name = label("light", light.index(), light.name());
    let invalid = |reason: String| SceneError::InvalidLight {
        file: file.to_owned(),
        light: name.clone(),
        reason,
    };
    // `gltf` parses these as f32: anything beyond f32's range arrives as infinity.
    let color = light.color();
    let values = [
        ("intensity", Some(light.intensity())),
        ("range", light.range()),
    ]
    .into_iter()
    .chain(color.map(|c| ("color", Some(c))));
    for (field, value) in values {
        if value.is_some_and(|v| !v.is_finite()) {
            return Err(invalid(format!(
                "{field} is beyond the largest f32 ({:e})",
                f32::MAX
            )));
        }
    }
    if light.intensity() < 0.0 {
        return Err(invalid(format!(
            "intensity {} is negative",
            light.intensity()
        )));
    }
    // A negative channel would subtract light; a light emitting nothing would be dropped
    // from drawing while the scene counted it.
    if color.iter().any(|c| *c < 0.0) {
        let [r, g, b] = color;
        return Err(invalid(format!(
            "color [{r}, {g}, {b}] has a negative channel; a light's color is linear RGB \
             from 0"
        )));
    }
    if let Some(range) = light.range().filter(|r| *r <= 0.0) {
        return Err(invalid(format!("range {range} is not positive")));
    }
    let kind = match light.kind() {
        Kind::Point => LightKind::Point,
        Kind::Directional => LightKind::Directional,
        Kind::Spot {
            inner_cone_angle,
            outer_cone_angle,
        } => {
            if !(0.0 <= inner_cone_angle
                && inner_cone_angle <= outer_cone_angle
                && outer_cone_angle <= FRAC_PI_2)
            {
                return Err(invalid(format!(
                    "spot cone angles inner {inner_cone_angle} / outer {outer_cone_angle} are \
                     not within 0 <= inner <= outer <= π/2"
                )));
            }
            LightKind::Spot {
                inner_cone: inner_cone_angle,
                outer_cone: outer_cone_angle,
            }
        }
    };
    Ok(Light {
        kind,
        color,
        intensity: light.intensity(),
        position: world.transform_point3(DVec3::ZERO),
        direction: world
            .transform_vector3(DVec3::NEG_Z)
            .normalize_or(DVec3::NEG_Z)
            .as_vec3(),
        range: light.range(),
        name,
    })
}
