//! Flat normals for meshes that come without them.

use glam::Vec3;

use super::mesh::Vertex;

/// The normal used for a degenerate (zero-area) triangle: any unit vector does, since the
/// triangle covers no pixels; a fixed one keeps results deterministic.
const DEGENERATE_NORMAL: [f32; 3] = [0.0, 0.0, 1.0];

/// Un-indexes a triangle list and gives every triangle its face normal, as glTF requires when
/// `NORMAL` is missing ("client implementations must calculate flat normals").
///
/// Indices must be in range of `vertices` and a multiple of 3 long; the vertices' normals are
/// ignored, their other attributes kept. Returns vertex `3 * t + k` for corner `k` of triangle
/// `t` and the identity index list. The normal follows the counter-clockwise winding:
/// `(b - a) x (c - a)`.
pub fn flat_shaded(vertices: &[Vertex], indices: &[u32]) -> (Vec<Vertex>, Vec<u32>) {
    let flat = indices
        .chunks_exact(3)
        .flat_map(|tri| {
            let corners = [0, 1, 2].map(|k| vertices[tri[k] as usize]);
            let [a, b, c] = corners.map(|v| Vec3::from_array(v.position));
            let normal = (b - a)
                .cross(c - a)
                .try_normalize()
                .map_or(DEGENERATE_NORMAL, |n| n.to_array());
            corners.map(|v| Vertex { normal, ..v })
        })
        .collect::<Vec<_>>();
    let indices = (0..flat.len() as u32).collect();
    (flat, indices)
}
