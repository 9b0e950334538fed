//! Triangle meshes: object-space vertex data plus a world transform.

use std::sync::Arc;

use glam::{DMat3, DMat4, DVec3, Vec3};

use super::bounds::Aabb;

/// One vertex as the G-buffer pass reads it: 56 bytes, no padding, uploadable as is.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct Vertex {
    /// Object space.
    pub position: [f32; 3],
    /// Object space. Unit length when generated; as stored when loaded (glTF requires unit
    /// length, quantized normals only approximate it), so shaders should renormalize.
    /// Zero on all three corners of a triangle asks for its face normal (the counter-clockwise
    /// one), which the renderers compute: a glTF mesh without `NORMAL` loads so, its vertices
    /// shared as the file indexes them.
    pub normal: [f32; 3],
    /// TEXCOORD_0; `[0, 0]` when the source has none.
    pub uv: [f32; 2],
    /// COLOR_0, linear RGBA as 16-bit unorm (a multiplier of the base color: 8 bits would
    /// band dark linear colors, floats would take 8 more bytes); [`Vertex::WHITE`] when the
    /// source has none.
    pub color: [u16; 4],
    /// Object-space tangent (xyz) and bitangent sign (w: bitangent = w * normal x tangent),
    /// as 16-bit snorm; [`Vertex::NO_TANGENT`] where no normal texture needs one.
    pub tangent: [i16; 4],
    /// TEXCOORD_1; `[0, 0]` when the source has none.
    pub uv1: [f32; 2],
}

impl Vertex {
    /// The color of vertices without COLOR_0: multiplies the base color by exactly one.
    pub const WHITE: [u16; 4] = [u16::MAX; 4];

    /// The tangent of vertices without one: shaders leave the normal unperturbed.
    pub const NO_TANGENT: [i16; 4] = [0; 4];

    /// `rgba` (components in [0, 1], clamped) as [`Vertex::color`] stores it.
    pub fn color_from(rgba: [f32; 4]) -> [u16; 4] {
        rgba.map(|c| (c.clamp(0.0, 1.0) * f32::from(u16::MAX)).round() as u16)
    }

    /// `xyzw` (components in [-1, 1], clamped) as [`Vertex::tangent`] stores it.
    pub fn tangent_from(xyzw: [f32; 4]) -> [i16; 4] {
        xyzw.map(|c| (c.clamp(-1.0, 1.0) * f32::from(i16::MAX)).round() as i16)
    }
}

/// The most meshes (glTF primitive placements) a scene may have: 1,048,576. The renderers
/// keep 128 bytes of per-mesh data (transform, normal matrix, material) in one storage
/// binding, and 2^20 of them fill the 128 MiB every WebGPU device binds; more failed on
/// lavapipe with a raw validation error. A city of 1,023 x 1,023 buildings fits.
pub const MAX_MESHES: u32 = 1 << 20;

/// An indexed triangle list with one material.
///
/// Vertex data stays in object space and the world transform is kept apart, in f64, so a renderer
/// can build camera-relative matrices for scenes far from the origin without losing precision.
/// Contract: every index is `< vertices.len()`, `indices.len()` is a multiple of 3, and triangles
/// are counter-clockwise when seen from their front side *after* `transform`, and tangent
/// signs are those of the world-space frame (loaders reverse the winding and the signs of
/// mirroring transforms so renderers need not).
///
/// Shared geometry: `vertices` and `indices` are reference-counted so that meshes placing
/// one geometry many times (glTF nodes and EXT_mesh_gpu_instancing instances placing one
/// primitive, built-in scenes of copies) hold it once; cloning a mesh shares them. Sharing
/// means equal contents, never aliasing writes: whoever mutates a mesh's geometry does so
/// through [`Arc::make_mut`], which copies it first when another mesh shares it, so no
/// mutation reaches another mesh. Renderers may upload a shared array once (it is the same
/// array when [`Arc::ptr_eq`] says so). Geometry that differs per placement is not shared:
/// the glTF loader gives the mirrored placements of a primitive one copy of their own (it
/// reverses their winding and tangent signs, above), and every deformed (skinned or morphed)
/// placement its own (the deformation writes the placement's vertices on the device).
/// Memory limits count a shared array once.
#[derive(Clone, Debug, PartialEq)]
pub struct Mesh {
    /// `mesh name/primitive index` for glTF, a description for built-in scenes.
    pub name: String,
    /// Object-space vertices, perhaps shared with other meshes (see above).
    pub vertices: Arc<Vec<Vertex>>,
    /// Triangle list, three indices per triangle, perhaps shared with other meshes.
    pub indices: Arc<Vec<u32>>,
    /// Index into `Scene::materials`.
    pub material: usize,
    /// Object space to world space.
    pub transform: DMat4,
}

impl Mesh {
    /// Triangles in the index list.
    pub fn triangle_count(&self) -> usize {
        self.indices.len() / 3
    }

    /// Object-space normals to world space: the inverse transpose of the transform's 3x3 part,
    /// so non-uniform scale keeps normals perpendicular to surfaces. Renormalize after use.
    pub fn normal_matrix(&self) -> DMat3 {
        DMat3::from_mat4(self.transform).inverse().transpose()
    }

    /// World-space positions of all vertices.
    pub fn world_positions(&self) -> impl Iterator<Item = DVec3> + '_ {
        self.vertices.iter().map(|v| {
            self.transform
                .transform_point3(Vec3::from_array(v.position).as_dvec3())
        })
    }

    /// Exact world-space bounds (every vertex transformed), `None` without vertices.
    pub fn world_bounds(&self) -> Option<Aabb> {
        Aabb::from_points(self.world_positions())
    }
}
