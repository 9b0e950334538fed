//! The view depths the camera sees of the scene's geometry, on the CPU from the frame's
//! inputs: for each mesh's bounding box (a shadow receiver's, blended or not), the depths of its intersection with the
//! view frustum (exact for the box: both solids are convex hexahedra, and every vertex of
//! their intersection is a vertex of one's faces clipped by the other's planes), united
//! over the meshes. The directional lights' cascades split this range
//! (gpu_scene/shadows.rs) rather than the near plane to the far: a stand-in for SDSM's
//! depth reduction that needs no read-back, and tighter than the scene's bounding sphere,
//! which reaches behind the camera whenever the camera is inside it.
//!
//! The range is rounded outward to powers of [`STEP`], so that a moving camera keeps its
//! cascades' sizes (and their texel grids) until the seen range crosses a step.

use glam::DVec3;
use rgraph_scene::{Aabb, Camera, Projection};

/// The ratio between consecutive depths the seen range is rounded to: the range is at
/// most this much looser at each end than the geometry's.
pub(super) const STEP: f64 = 1.090_507_732_665_257_7; // 2^(1/8)

/// The view depths `[near, far]` (along the camera's forward axis, within its near and
/// far planes) of the parts of `boxes` (camera-relative) inside the view frustum at
/// `aspect` (width over height), rounded outward to powers of [`STEP`]; `None` when no
/// box reaches into the frustum.
pub(super) fn seen_depths(camera: &Camera, aspect: f64, boxes: &[Aabb]) -> Option<(f64, f64)> {
    let (znear, zfar) = match camera.projection {
        Projection::Perspective { znear, zfar, .. } => (znear, zfar.unwrap_or(f32::INFINITY)),
        Projection::Orthographic { znear, zfar, .. } => (znear, zfar),
    };
    let (znear, zfar) = (f64::from(znear), f64::from(zfar));
    let to_view = camera.orientation.inverse();
    let (near, far) = boxes
        .iter()
        .filter_map(|b| box_depths(camera, aspect, to_view, b, znear, zfar))
        .reduce(|a, b| (a.0.min(b.0), a.1.max(b.1)))?;
    let round = |d: f64, step: fn(f64) -> f64| STEP.powf(step(d.ln() / STEP.ln()));
    let far = round(far, f64::ceil).min(zfar);
    let near = match near > 0.0 {
        true => round(near, f64::floor).max(znear),
        // An orthographic camera's near plane may be at 0, where the logarithmic split
        // would put every cascade: start the range a ten-thousandth of its far end out.
        false => far * 1e-4,
    };
    (far > near).then_some((near, far))
}

/// The depths of `b`'s part inside the frustum between `znear` and `zfar`.
fn box_depths(
    camera: &Camera,
    aspect: f64,
    to_view: glam::DQuat,
    b: &Aabb,
    znear: f64,
    zfar: f64,
) -> Option<(f64, f64)> {
    // A flat box (a ground plane's) would have coincident faces and planes without an
    // inside; padding it a little keeps both solids proper.
    let pad = DVec3::splat(1e-6 * (1.0 + b.size().length()));
    let padded = Aabb {
        min: b.min - pad,
        max: b.max + pad,
    };
    let solid = Hexahedron(padded.corners().map(|c| to_view * c));
    let deepest = solid.0.iter().map(|c| -c.z).fold(f64::MIN, f64::max);
    let shallowest = solid.0.iter().map(|c| -c.z).fold(f64::MAX, f64::min);
    // Most boxes are wholly in view or wholly out of it (a city seen whole, a million
    // buildings): their corners against the frustum's six planes say so without
    // clipping. Each side is linear in the point, so all corners outside one plane is
    // the whole box outside it.
    let sides = solid.0.map(|p| {
        let d = -p.z;
        let (x, y) = half_extent(camera, aspect, d);
        [d - znear, zfar - d, x - p.x, x + p.x, y - p.y, y + p.y]
    });
    if (0..6).any(|i| sides.iter().all(|s| s[i] < 0.0)) {
        return None;
    }
    if sides.iter().flatten().all(|&s| s >= 0.0) {
        return Some((shallowest, deepest));
    }
    let frustum = frustum(camera, aspect, znear, zfar.min(deepest));
    let depths = solid
        .clipped_by(&frustum)
        .chain(frustum.clipped_by(&solid))
        .map(|p| -p.z);
    depths.fold(None, |range, d| match range {
        None => Some((d, d)),
        Some((a, b)) => Some((f64::min(a, d), f64::max(b, d))),
    })
}

/// Half the view's width and height at view depth `d` (negative behind a perspective
/// camera, so that the sides stay linear).
fn half_extent(camera: &Camera, aspect: f64, d: f64) -> (f64, f64) {
    match camera.projection {
        Projection::Perspective { yfov, .. } => {
            let tan_y = f64::from(yfov * 0.5).tan();
            (d * tan_y * aspect, d * tan_y)
        }
        Projection::Orthographic { ymag, .. } => (f64::from(ymag) * aspect, f64::from(ymag)),
    }
}

/// The view frustum between depths `near` and `far`, in view space, as a hexahedron.
fn frustum(camera: &Camera, aspect: f64, near: f64, far: f64) -> Hexahedron {
    Hexahedron(std::array::from_fn(|i| {
        let d = if i & 4 != 0 { far } else { near };
        let (x, y) = half_extent(camera, aspect, d);
        let sign = |bit: usize| if i & bit != 0 { 1.0 } else { -1.0 };
        DVec3::new(sign(1) * x, sign(2) * y, -d)
    }))
}

/// A convex solid with six quadrilateral faces, its corners indexed as
/// [`Aabb::corners`]'s are (bit 0 the first axis's end, bit 1 the second's, bit 2 the
/// third's).
struct Hexahedron([DVec3; 8]);

/// The faces' corners, in order around each face.
const FACES: [[usize; 4]; 6] = [
    [0, 2, 6, 4],
    [1, 3, 7, 5],
    [0, 1, 5, 4],
    [2, 3, 7, 6],
    [0, 1, 3, 2],
    [4, 5, 7, 6],
];

impl Hexahedron {
    /// The planes of its faces as `(n, d)`, `n · p + d >= 0` inside.
    fn planes(&self) -> impl Iterator<Item = (DVec3, f64)> + '_ {
        let centre = self.0.iter().sum::<DVec3>() / 8.0;
        FACES.iter().map(move |face| {
            // Newell's normal: sound for a face with a degenerate edge.
            let normal: DVec3 = (0..4)
                .map(|i| self.0[face[i]].cross(self.0[face[(i + 1) % 4]]))
                .sum();
            let normal = normal.normalize_or_zero();
            let d = -normal.dot(self.0[face[0]]);
            match normal.dot(centre) + d >= 0.0 {
                true => (normal, d),
                false => (-normal, -d),
            }
        })
    }

    /// The vertices of its faces clipped by `other`'s planes.
    fn clipped_by<'a>(&'a self, other: &'a Hexahedron) -> impl Iterator<Item = DVec3> + 'a {
        FACES
            .iter()
            .flat_map(move |face| other.planes().fold(face.map(|i| self.0[i]).to_vec(), clip))
    }
}

/// `polygon` cut to the inside of `plane` (Sutherland-Hodgman).
fn clip(polygon: Vec<DVec3>, (n, d): (DVec3, f64)) -> Vec<DVec3> {
    let side = |p: DVec3| n.dot(p) + d;
    let mut out = Vec::with_capacity(polygon.len() + 1);
    for (i, &p) in polygon.iter().enumerate() {
        let q = polygon[(i + 1) % polygon.len()];
        let (sp, sq) = (side(p), side(q));
        if sp >= 0.0 {
            out.push(p);
        }
        if (sp >= 0.0) != (sq >= 0.0) {
            out.push(p + (q - p) * (sp / (sp - sq)));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn camera(eye: DVec3, target: DVec3) -> Camera {
        let projection = Projection::Perspective {
            yfov: 0.8,
            znear: 0.1,
            zfar: None,
        };
        Camera::look_at("c", eye, target, DVec3::Y, projection)
    }

    /// The exact range, before rounding, is within a step of what is returned.
    fn assert_rounded(got: (f64, f64), exact: (f64, f64)) {
        assert!(
            got.0 <= exact.0 + 1e-3 && got.0 * STEP >= exact.0 - 1e-3,
            "near {} for {}",
            got.0,
            exact.0
        );
        assert!(
            got.1 >= exact.1 - 1e-3 && got.1 <= exact.1 * STEP + 1e-3,
            "far {} for {}",
            got.1,
            exact.1
        );
    }

    /// A box wholly in view: its nearest and farthest corners' depths.
    #[test]
    fn a_box_in_view_gives_its_corners_depths() {
        let cam = camera(DVec3::ZERO, DVec3::NEG_Z);
        let b = Aabb {
            min: DVec3::new(-1.0, -1.0, -9.0),
            max: DVec3::new(1.0, 1.0, -4.0),
        };
        let got = seen_depths(&cam, 1.5, &[b]).expect("in view");
        assert_rounded(got, (4.0, 9.0));
        // A box behind the camera or wholly off to the side is not seen.
        let behind = Aabb {
            min: DVec3::new(-1.0, -1.0, 2.0),
            max: DVec3::new(1.0, 1.0, 5.0),
        };
        let aside = Aabb {
            min: DVec3::new(50.0, -1.0, -9.0),
            max: DVec3::new(52.0, 1.0, -4.0),
        };
        assert_eq!(seen_depths(&cam, 1.5, &[behind, aside]), None);
        assert_eq!(seen_depths(&cam, 1.5, &[b, behind, aside]), Some(got));
    }

    /// Geometry reaching an orthographic camera's near plane at 0 gives a range that
    /// starts past 0, which the logarithmic split can divide.
    #[test]
    fn an_orthographic_range_from_zero_starts_past_it() {
        let projection = Projection::Orthographic {
            xmag: 2.0,
            ymag: 2.0,
            znear: 0.0,
            zfar: 100.0,
        };
        let cam = Camera::look_at("o", DVec3::ZERO, DVec3::NEG_Z, DVec3::Y, projection);
        let b = Aabb {
            min: DVec3::new(-1.0, -1.0, -10.0),
            max: DVec3::new(1.0, 1.0, 3.0),
        };
        let (near, far) = seen_depths(&cam, 1.0, &[b]).expect("in view");
        assert!((10.0..=10.0 * STEP).contains(&far), "far {far}");
        assert_eq!(near, far * 1e-4);
    }

    /// A ground plane running under and behind a camera that looks down at it: the
    /// nearest depth seen is where the frustum's lower plane meets the ground (not the
    /// camera's near plane), the farthest where its upper plane does.
    #[test]
    fn a_ground_plane_is_seen_from_the_frustum_s_lower_edge() {
        // Two units up, looking 30 degrees down.
        let pitch = 30f64.to_radians();
        let cam = camera(
            DVec3::new(0.0, 2.0, 0.0),
            DVec3::new(0.0, 2.0 - pitch.sin(), -pitch.cos()),
        );
        // Camera-relative: the ground is 2 units below.
        let ground = Aabb {
            min: DVec3::new(-100.0, -2.0, -100.0),
            max: DVec3::new(100.0, -2.0, 100.0),
        };
        let (near, far) = seen_depths(&cam, 1.0, &[ground]).expect("seen");
        // The frustum's lower edge runs pitch + yfov/2 down: per unit of view depth it
        // drops sin(pitch + 0.4) / cos(0.4), the same at its corners (the camera's right
        // is level), so it meets the ground at depth 2 cos(0.4) / sin(pitch + 0.4); its
        // upper edge, pitch - yfov/2 down, at 2 cos(0.4) / sin(pitch - 0.4).
        let at = |down: f64| 2.0 * 0.4f64.cos() / down.sin();
        assert_rounded((near, far), (at(pitch + 0.4), at(pitch - 0.4)));
        assert!(near > 1.0, "near {near}: far past the camera's near plane");
    }
}
