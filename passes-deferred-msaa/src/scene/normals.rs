//! Flat normals for meshes that come without them.

use glam::Vec3;

use super::mesh::Vertex;

/// The normal used for a degenerate (zero-area) triangle: any unit vector does, since the
/// triangle covers no pixels; a fixed one keeps results deterministic.
const DEGENERATE_NORMAL: [f32; 3] = [0.0, 0.0, 1.0];

/// Un-indexes a triangle list and gives every triangle its face normal, as glTF requires when
/// `NORMAL` is missing ("client implementations must calculate flat normals").
///
/// `uvs` is either empty (uv = 0) or as long as `positions`; indices must be in range and a
/// multiple of 3 long. Returns vertex `3 * t + k` for corner `k` of triangle `t` and the
/// identity index list. The normal follows the counter-clockwise winding: `(b - a) x (c - a)`.
pub fn flat_shaded(
    positions: &[[f32; 3]],
    uvs: &[[f32; 2]],
    indices: &[u32],
) -> (Vec<Vertex>, Vec<u32>) {
    let vertices = indices
        .chunks_exact(3)
        .flat_map(|tri| {
            let [a, b, c] = [0, 1, 2].map(|k| Vec3::from_array(positions[tri[k] as usize]));
            let normal = (b - a)
                .cross(c - a)
                .try_normalize()
                .map_or(DEGENERATE_NORMAL, |n| n.to_array());
            tri.iter().map(move |&i| Vertex {
                position: positions[i as usize],
                normal,
                uv: uvs.get(i as usize).copied().unwrap_or([0.0; 2]),
            })
        })
        .collect::<Vec<_>>();
    let indices = (0..vertices.len() as u32).collect();
    (vertices, indices)
}
