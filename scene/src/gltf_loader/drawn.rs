//! Which primitives become triangle meshes (triangles, strips and fans, see `primitive`)
//! and which points or lines (see `points_lines`). Every primitive is drawn.

use gltf::mesh::Mode;

/// Whether `primitive` is of a triangle mode: a [`Mesh`](crate::Mesh), not a
/// [`PointsLines`](crate::PointsLines).
pub(super) fn is_triangles(primitive: &gltf::Primitive) -> bool {
    matches!(
        primitive.mode(),
        Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan
    )
}
