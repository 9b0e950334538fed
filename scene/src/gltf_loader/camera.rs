//! glTF cameras to [`Camera`]s.

use std::path::Path;

use glam::DMat4;
use gltf::json::camera::Type;
use gltf::json::validation::Checked;

use crate::error::label;
use crate::{Camera, Projection, SceneError, MAX_COORDINATE};

/// The smallest perspective znear. With reversed-Z a point at distance `d` gets depth
/// `znear / d`, and GPUs flush values below f32's smallest normal number (1.2e-38) to 0,
/// the far plane, where nothing is drawn: the frame would be empty. Every point of a scene
/// lies within ±[`MAX_COORDINATE`], so within `2√3 · MAX_COORDINATE` of the camera; from
/// this znear on, every depth is a normal number.
pub(crate) const MIN_ZNEAR: f32 = (f32::MIN_POSITIVE as f64 * 4.0 * MAX_COORDINATE) as f32;

/// Converts a camera placed at `world`. The node's scale is dropped (glTF cameras look down
/// their node's -Z with +Y up whatever the scale). Rejects projections that cannot make a
/// matrix: a value that is not a finite f32 (`1e39` in the file), yfov outside (0, π),
/// znear <= 0 for perspective (< 0 for orthographic), zfar <= znear, zero xmag or ymag; and
/// a perspective znear below [`MIN_ZNEAR`], which would draw nothing.
pub(super) fn convert(
    file: &Path,
    document: &gltf::Document,
    camera: &gltf::Camera,
    world: &DMat4,
) -> Result<Camera, SceneError> {
    let name = label("camera", camera.index(), camera.name());
    let invalid = |reason: &str| SceneError::InvalidCamera {
        file: file.to_owned(),
        camera: name.clone(),
        reason: reason.to_owned(),
    };
    // The JSON is read directly: gltf's `Camera::projection` unwraps the object named by
    // `type`, which a malformed file may lack.
    let json = &document.as_json().cameras[camera.index()];
    // `gltf` parses these as f32: anything beyond f32's range arrives as infinity.
    let finite = |values: &[(&str, Option<f32>)]| match values
        .iter()
        .find(|(_, v)| v.is_some_and(|v| !v.is_finite()))
    {
        Some((field, _)) => Err(invalid(&format!(
            "{field} is beyond the largest f32 ({:e})",
            f32::MAX
        ))),
        None => Ok(()),
    };
    let projection = match (&json.type_, &json.perspective, &json.orthographic) {
        (Checked::Valid(Type::Perspective), Some(p), _) => {
            finite(&[
                ("yfov", Some(p.yfov)),
                ("znear", Some(p.znear)),
                ("zfar", p.zfar),
                ("aspectRatio", p.aspect_ratio),
            ])?;
            if p.yfov <= 0.0 || p.yfov >= std::f32::consts::PI {
                return Err(invalid("yfov must be in (0, π)"));
            }
            if p.znear <= 0.0 || p.zfar.is_some_and(|zfar| zfar <= p.znear) {
                return Err(invalid("perspective needs 0 < znear < zfar"));
            }
            if p.znear < MIN_ZNEAR {
                return Err(invalid(&format!(
                    "znear {:e} is below {MIN_ZNEAR:.1e}: depths (znear / distance) would \
                     fall below the smallest normal f32, which GPUs flush to the far plane, \
                     and the frame would be empty",
                    p.znear
                )));
            }
            Projection::Perspective {
                yfov: p.yfov,
                znear: p.znear,
                zfar: p.zfar,
            }
        }
        (Checked::Valid(Type::Orthographic), _, Some(o)) => {
            finite(&[
                ("xmag", Some(o.xmag)),
                ("ymag", Some(o.ymag)),
                ("znear", Some(o.znear)),
                ("zfar", Some(o.zfar)),
            ])?;
            if o.xmag == 0.0 || o.ymag == 0.0 {
                return Err(invalid("xmag and ymag must not be zero"));
            }
            if o.znear < 0.0 || o.zfar <= o.znear {
                return Err(invalid("orthographic needs 0 <= znear < zfar"));
            }
            Projection::Orthographic {
                xmag: o.xmag,
                ymag: o.ymag,
                znear: o.znear,
                zfar: o.zfar,
            }
        }
        _ => {
            return Err(invalid(
                "`type` does not match a perspective or orthographic object",
            ))
        }
    };
    let (_, orientation, position) = world.to_scale_rotation_translation();
    if !orientation.is_finite() {
        return Err(invalid(
            "its node's transform has zero scale, so it has no orientation",
        ));
    }
    Ok(Camera {
        name,
        position,
        orientation,
        projection,
    })
}
