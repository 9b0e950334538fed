//! The depth range a scene puts between the camera's planes.

use glam::DVec3;

use crate::scene::{Projection, Scene};

/// Distances along the view axis from the camera to the nearest and farthest geometry,
/// clamped to the camera's near and far planes. Their ratio is what depth precision
/// must span: a depth format and reversed-Z could be chosen from it (not done yet).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DepthRange {
    pub near: f64,
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
}

/// The near and far plane distances (infinity for an infinite far plane).
pub(super) fn planes(projection: &Projection) -> (f64, f64) {
    match *projection {
        Projection::Perspective { znear, zfar, .. } => {
            (f64::from(znear), zfar.map_or(f64::INFINITY, f64::from))
        }
        Projection::Orthographic { znear, zfar, .. } => (f64::from(znear), f64::from(zfar)),
    }
}
