//! Where each mesh's vertices and indices lie in the scene's buffers, with the geometry
//! meshes share (see [`rgraph_scene::Mesh`]) held once.
//!
//! Vertices: each distinct vertex array is uploaded once, and every mesh sharing it draws
//! it through the same base vertex. Clusters: each distinct geometry (vertex and index
//! arrays together) is clustered once, and its clusters and their boxes serve every mesh
//! placing it. Indices: every mesh keeps its own range of the cluster-ordered indices, a
//! copy per placement, because a visibility buffer's triangle ID is an index position / 3
//! and must name one placement: with one range shared, every instance's triangles would
//! carry one ID, and shading could not tell which transform drew them.
//!
//! A scene that deforms shares no vertices: the deformation pass (deform.rs) binds the
//! range from the first deformed mesh's vertices to the last's, taking the meshes' places
//! from this layout, and writes the deformed ones over their own.

use std::collections::HashMap;

use rgraph_scene::{Mesh, Scene, Vertex};

/// One mesh's place in the scene's buffers.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Placement {
    /// Where its indices start in the index buffer.
    pub first_index: u32,
    /// Added to its indices: where its vertex array starts in the vertex buffer.
    pub base_vertex: i32,
    /// Its geometry in [`GeometryLayout::shape_owners`] order.
    pub shape: u32,
}

/// The scene's buffers laid out: computed once per scene, kept across its frames.
#[derive(Debug, PartialEq)]
pub(super) struct GeometryLayout {
    /// One per mesh, in `Scene::meshes` order.
    pub placements: Vec<Placement>,
    /// The vertex buffer's contents: the first mesh holding each distinct vertex array,
    /// in buffer order.
    pub vertex_owners: Vec<usize>,
    /// The first mesh holding each distinct geometry, in shape order.
    pub shape_owners: Vec<usize>,
}

impl GeometryLayout {
    pub fn new(scene: &Scene) -> GeometryLayout {
        let deforms = !scene.deformations.is_empty();
        let mut layout = GeometryLayout {
            placements: Vec::with_capacity(scene.meshes.len()),
            vertex_owners: Vec::new(),
            shape_owners: Vec::new(),
        };
        let mut bases: HashMap<*const Vec<Vertex>, i32> = HashMap::new();
        let mut shapes: HashMap<(*const Vec<Vertex>, *const Vec<u32>), u32> = HashMap::new();
        let (mut first_index, mut vertex_count) = (0u32, 0i32);
        for (index, mesh) in scene.meshes.iter().enumerate() {
            let Mesh {
                vertices, indices, ..
            } = mesh;
            let vertex_key = std::sync::Arc::as_ptr(vertices);
            let shared_base = bases.get(&vertex_key).filter(|_| !deforms);
            let base_vertex = match shared_base {
                Some(&base) => base,
                None => {
                    bases.insert(vertex_key, vertex_count);
                    layout.vertex_owners.push(index);
                    vertex_count += vertices.len() as i32;
                    vertex_count - vertices.len() as i32
                }
            };
            let next_shape = layout.shape_owners.len() as u32;
            let shape = *shapes
                .entry((vertex_key, std::sync::Arc::as_ptr(indices)))
                .or_insert_with(|| {
                    layout.shape_owners.push(index);
                    next_shape
                });
            layout.placements.push(Placement {
                first_index,
                base_vertex,
                shape,
            });
            first_index += indices.len() as u32;
        }
        layout
    }

    /// The bytes of the scene's vertex and index buffers as laid out, named: the
    /// distinct vertex arrays once, every mesh's indices.
    pub fn buffer_bytes(&self, scene: &Scene) -> [(&'static str, u64); 2] {
        let vertices: u64 = (self.vertex_owners.iter())
            .map(|&mesh| scene.meshes[mesh].vertices.len() as u64)
            .sum();
        let indices: u64 = (scene.meshes.iter())
            .map(|mesh| mesh.indices.len() as u64)
            .sum();
        [
            ("vertices", vertices * std::mem::size_of::<Vertex>() as u64),
            ("indices", indices * std::mem::size_of::<u32>() as u64),
        ]
    }
}
