//! The depth range a scene puts between the camera's planes.

use glam::DVec3;

use crate::{Projection, Scene};

/// Distances along the view axis from the camera to the nearest and farthest geometry,
/// clamped to the camera's near and far planes. Their ratio is what depth precision
/// must span: [`shallow`](Self::shallow) says whether a 24-bit unorm depth buffer with
/// standard Z spans it, which is how pipelines pick their depth format (feature
/// `shallow_depth`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DepthRange {
    /// Distance to the nearest geometry, world units, at least the near plane's.
    pub near: f64,
    /// Distance to the farthest geometry, world units, at most the far plane's.
    pub far: f64,
}

impl DepthRange {
    /// Over every vertex: exact for the geometry, though a triangle may reach nearer or
    /// farther than its vertices only where a plane cuts it, which the clamp covers.
    /// `None` when all geometry lies in front of the near plane or beyond the far one.
    pub fn of(scene: &Scene) -> Option<DepthRange> {
        let camera = &scene.camera;
        let (eye, forward) = (camera.position, camera.forward());
        let depth = |p: DVec3| (p - eye).dot(forward);
        let (nearest, farthest) = scene
            .meshes
            .iter()
            .flat_map(|m| m.world_positions())
            .map(depth)
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), d| {
                (lo.min(d), hi.max(d))
            });
        let (znear, zfar) = planes(&camera.projection);
        let range = DepthRange {
            near: nearest.max(znear),
            far: farthest.min(zfar),
        };
        (range.near <= range.far).then_some(range)
    }

    /// `far / near`: how many times farther the farthest geometry is than the nearest.
    pub fn ratio(&self) -> f64 {
        self.far / self.near
    }

    /// The coarsest step of a 24-bit unorm depth buffer with standard Z over the range,
    /// relative to the distance it is at, seen through `projection` (the camera the
    /// range was measured with).
    ///
    /// Why these measures: a unorm depth buffer steps by 2^-24 of the clip depth.
    /// - Perspective, standard Z: the clip depth at distance `z` is about `1 - znear/z`,
    ///   so one step spans `z² / (znear·2^24)` of distance, `z / (znear·2^24)` relative
    ///   to `z`. That grows with distance: the farthest geometry's `far / znear` (the
    ///   camera's near plane, not the nearest geometry's distance) decides.
    /// - Orthographic: the clip depth is linear, one step is `(zfar - znear) / 2^24`
    ///   everywhere, and relative to the distance it is coarsest at the nearest geometry.
    pub fn unorm24_step(&self, projection: &Projection) -> f64 {
        let (znear, zfar) = planes(projection);
        let span = match projection {
            Projection::Perspective { .. } => self.far / znear,
            Projection::Orthographic { .. } => (zfar - znear) / self.near,
        };
        span * UNORM24_STEP
    }

    /// Whether 24-bit unorm depth with standard Z separates surfaces as finely as
    /// [`SHALLOW_STEP`] of their distance everywhere in the range
    /// ([`unorm24_step`](Self::unorm24_step)).
    ///
    /// Reversed-Z buys nothing in a unorm format (its steps are uniform either way); it
    /// is float depth (`depth32float`) that it evens out. So where this holds, the
    /// smaller unorm format with standard Z renders what float reversed-Z does.
    pub fn shallow(&self, projection: &Projection) -> bool {
        self.unorm24_step(projection) <= SHALLOW_STEP
    }
}

/// One step of a 24-bit unorm depth buffer, in clip depth.
const UNORM24_STEP: f64 = 1.0 / (1u32 << 24) as f64;

/// The coarsest depth step, relative to the distance, that [`DepthRange::shallow`]
/// accepts: 2^-14 (about 6e-5, 0.06 mm at one metre). In perspective that is a far
/// distance of 1024 times the near plane. Surfaces nearer each other than that may
/// fight; modelled scenes rarely put distinct surfaces that close, and the float
/// format's reversed-Z would resolve them only a little better where they are near.
pub const SHALLOW_STEP: f64 = 1.0 / (1u32 << 14) as f64;

/// The near and far plane distances (infinity for an infinite far plane).
pub(super) fn planes(projection: &Projection) -> (f64, f64) {
    match *projection {
        Projection::Perspective { znear, zfar, .. } => {
            (f64::from(znear), zfar.map_or(f64::INFINITY, f64::from))
        }
        Projection::Orthographic { znear, zfar, .. } => (f64::from(znear), f64::from(zfar)),
    }
}

#[cfg(test)]
mod tests {
    use super::{DepthRange, SHALLOW_STEP};
    use crate::Projection;

    fn perspective(znear: f32) -> Projection {
        Projection::Perspective {
            yfov: 0.8,
            znear,
            zfar: None,
        }
    }

    fn orthographic(znear: f32, zfar: f32) -> Projection {
        Projection::Orthographic {
            xmag: 1.0,
            ymag: 1.0,
            znear,
            zfar,
        }
    }

    #[test]
    fn perspective_is_shallow_up_to_a_far_distance_of_1024_near_planes() {
        let range = |far| DepthRange { near: 1.0, far };
        assert!(range(102.4).shallow(&perspective(0.1)));
        assert!(!range(102.4 * 1.01).shallow(&perspective(0.1)));
        // The camera's near plane decides, not the nearest geometry.
        assert!(!range(50.0).shallow(&perspective(0.01)));
    }

    #[test]
    fn orthographic_is_shallow_while_its_plane_span_is_1024_nearest_distances() {
        let range = |near| DepthRange { near, far: 20.0 };
        assert!(range(1.0).shallow(&orthographic(0.0, 1024.0)));
        assert!(!range(0.99).shallow(&orthographic(0.0, 1024.0)));
        assert!(range(0.01).shallow(&orthographic(0.0, 10.0)));
    }

    #[test]
    fn the_threshold_is_2_to_the_minus_14() {
        assert_eq!(SHALLOW_STEP, 2f64.powi(-14));
    }
}
