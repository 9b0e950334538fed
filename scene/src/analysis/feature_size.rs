//! The smallest detail a scene puts on screen, estimated from its triangle edges.

use glam::DVec3;

use super::depth::planes;
use crate::{Projection, Scene};

/// The shortest triangle edge between the camera's planes, in pixels at its distance.
/// An estimate: each edge counts as if it were parallel to the image plane (so
/// foreshortening can only make the true size smaller), at its midpoint's depth, and
/// edges outside the view's sides count too. Degenerate edges (length 0) cover nothing
/// and do not count.
#[derive(Clone, Debug, PartialEq)]
pub struct SmallestFeature {
    /// The edge's length in pixels at its distance.
    pub pixels: f64,
    /// The mesh the edge belongs to.
    pub mesh: String,
    /// The edge's midpoint's distance along the view axis.
    pub depth: f64,
}

impl SmallestFeature {
    /// At an output of `output` (width, height) pixels.
    pub fn of(scene: &Scene, output: (u32, u32)) -> Option<SmallestFeature> {
        let camera = &scene.camera;
        let (eye, forward) = (camera.position, camera.forward());
        let (znear, zfar) = planes(&camera.projection);
        let height = f64::from(output.1);
        // Pixels per world unit at distance `d` in the image plane.
        let scale = |d: f64| match camera.projection {
            Projection::Perspective { yfov, .. } => {
                height / (2.0 * d * (f64::from(yfov) * 0.5).tan())
            }
            Projection::Orthographic { ymag, .. } => height / (2.0 * f64::from(ymag)),
        };
        let mut smallest: Option<SmallestFeature> = None;
        for mesh in &scene.meshes {
            let points: Vec<DVec3> = mesh.world_positions().collect();
            for triangle in mesh.indices.chunks_exact(3) {
                for (a, b) in [(0, 1), (1, 2), (2, 0)] {
                    let (p, q) = (points[triangle[a] as usize], points[triangle[b] as usize]);
                    let length = p.distance(q);
                    let depth = ((p + q) * 0.5 - eye).dot(forward);
                    if length == 0.0 || depth < znear || depth > zfar {
                        continue;
                    }
                    let pixels = length * scale(depth);
                    if smallest.as_ref().is_none_or(|s| pixels < s.pixels) {
                        smallest = Some(SmallestFeature {
                            pixels,
                            mesh: mesh.name.clone(),
                            depth,
                        });
                    }
                }
            }
        }
        smallest
    }
}
