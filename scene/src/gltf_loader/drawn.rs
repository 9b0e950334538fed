//! Which primitives are drawn: triangles, strips and fans. Points and lines are skipped
//! with a warning (see `primitive`).

use gltf::mesh::Mode;

/// The primitives of `mesh` that are drawn.
pub(super) fn primitives<'a>(mesh: &gltf::Mesh<'a>) -> impl Iterator<Item = gltf::Primitive<'a>> {
    mesh.primitives().filter(is_drawn)
}

/// Whether `primitive` is drawn.
pub(super) fn is_drawn(primitive: &gltf::Primitive) -> bool {
    !matches!(
        primitive.mode(),
        Mode::Points | Mode::Lines | Mode::LineLoop | Mode::LineStrip
    )
}
