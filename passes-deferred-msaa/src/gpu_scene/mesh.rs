//! Scene geometry on the device: every mesh's vertices and indices in one buffer each, and
//! per-mesh data (camera-relative model matrix, normal matrix, material) in a storage
//! buffer the G-buffer vertex shader indexes with the instance index.

use glam::{DMat3, DMat4, DVec3, Vec3};
use wgpu::util::DeviceExt;

use crate::scene::{Aabb, Scene, Vertex};

/// `MeshData` in scene.wgsl.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct MeshData {
    model: [[f32; 4]; 4],
    /// mat3x3<f32>: three columns padded to 16 bytes.
    normal_matrix: [[f32; 4]; 3],
    material: u32,
    /// Where the mesh's indices start in the scene's index buffer, and what they add to
    /// reach the scene's vertex buffer: a visibility buffer's triangle ID is an index
    /// position / 3, and its shading pass pulls the triangle's vertices through these.
    first_index: u32,
    base_vertex: i32,
    _pad: u32,
}

/// One mesh's draw: `draw_indexed(indices, base_vertex, instance..instance + 1)`.
#[derive(Clone, Debug, PartialEq)]
pub struct MeshDraw {
    pub indices: std::ops::Range<u32>,
    pub base_vertex: i32,
    /// The mesh's index in `Scene::meshes`, which is also its instance index.
    pub instance: u32,
    /// Index into `Scene::materials`.
    pub material: usize,
    /// The centre of the mesh's world bounds, camera-relative: how far the draw is from
    /// the camera, for drawing blended meshes back to front. Kept beside `bounds` rather
    /// than taken from it: the world centre minus the eye is what the draws were always
    /// sorted by, and the centre of the camera-relative bounds rounds differently, which
    /// could reorder draws at nearly one distance.
    pub center: DVec3,
    /// The mesh's world bounds, camera-relative (a point at its origin without
    /// vertices): where on screen it may be.
    pub bounds: Aabb,
}

pub(super) struct MeshBuffers {
    pub vertices: wgpu::Buffer,
    pub indices: wgpu::Buffer,
    /// Per-mesh [`MeshData`], rewritten when the camera or a mesh moves.
    pub data: wgpu::Buffer,
}

/// The vertex layout of scene meshes: [`Vertex`] at locations 0 (position), 1 (normal),
/// 2 (uv), 3 (color), 4 (tangent) and 5 (uv1).
pub const VERTEX_LAYOUT: wgpu::VertexBufferLayout<'static> = wgpu::VertexBufferLayout {
    array_stride: std::mem::size_of::<Vertex>() as u64,
    step_mode: wgpu::VertexStepMode::Vertex,
    attributes: &wgpu::vertex_attr_array![
        0 => Float32x3, 1 => Float32x3, 2 => Float32x2, 3 => Unorm16x4, 4 => Snorm16x4,
        5 => Float32x2
    ],
};

/// The per-mesh data of one frame: what the data buffer holds and each mesh's draw.
#[derive(Clone)]
pub(super) struct MeshFrame {
    data: Vec<MeshData>,
    pub draws: Vec<MeshDraw>,
    /// Each mesh's world bounds, kept so that a frame moving the camera but not the mesh
    /// does not transform its vertices again.
    world_bounds: Vec<Aabb>,
}

impl MeshFrame {
    /// The meshes of `scene` placed by `transforms` (one per mesh) and seen from `eye`.
    /// `previous` is the frame before, whose bounds are reused for the meshes
    /// `transforms` does not move.
    pub fn new(
        scene: &Scene,
        transforms: &[DMat4],
        eye: DVec3,
        previous: Option<(&MeshFrame, &[DMat4])>,
    ) -> MeshFrame {
        let (mut index_count, mut vertex_count) = (0u32, 0i32);
        let mut frame = MeshFrame {
            data: Vec::new(),
            draws: Vec::new(),
            world_bounds: Vec::new(),
        };
        for ((mesh, &transform), instance) in scene.meshes.iter().zip(transforms).zip(0u32..) {
            let kept = previous.and_then(|(frame, transforms)| {
                (transforms.get(instance as usize) == Some(&transform))
                    .then(|| frame.world_bounds[instance as usize])
            });
            let world_bounds = kept.unwrap_or_else(|| {
                let positions = mesh
                    .vertices
                    .iter()
                    .map(|v| transform.transform_point3(Vec3::from_array(v.position).as_dvec3()));
                Aabb::from_points(positions).unwrap_or_else(|| {
                    let origin = transform.w_axis.truncate();
                    Aabb {
                        min: origin,
                        max: origin,
                    }
                })
            });
            frame.world_bounds.push(world_bounds);
            frame.draws.push(MeshDraw {
                indices: index_count..index_count + mesh.indices.len() as u32,
                base_vertex: vertex_count,
                instance,
                material: mesh.material,
                center: world_bounds.center() - eye,
                bounds: Aabb {
                    min: world_bounds.min - eye,
                    max: world_bounds.max - eye,
                },
            });
            index_count += mesh.indices.len() as u32;
            vertex_count += mesh.vertices.len() as i32;
            // Mesh::normal_matrix of the placed mesh.
            let normal = DMat3::from_mat4(transform).inverse().transpose().as_mat3();
            frame.data.push(MeshData {
                model: camera_relative(transform, eye),
                normal_matrix: [normal.x_axis, normal.y_axis, normal.z_axis]
                    .map(|c| c.extend(0.0).to_array()),
                material: mesh.material as u32,
                first_index: index_count - mesh.indices.len() as u32,
                base_vertex: vertex_count - mesh.vertices.len() as i32,
                _pad: 0,
            });
        }
        // A scene without meshes (a glTF scene listing no nodes) still binds the buffer:
        // wgpu refuses zero-sized storage bindings, and nothing is drawn.
        if frame.draws.is_empty() {
            frame.data.push(bytemuck::Zeroable::zeroed());
        }
        frame
    }

    /// The data buffer's contents.
    pub fn bytes(&self) -> &[u8] {
        bytemuck::cast_slice(&self.data)
    }
}

impl MeshBuffers {
    /// Uploads `scene`'s geometry and `frame`'s per-mesh data.
    pub fn new(device: &wgpu::Device, scene: &Scene, frame: &MeshFrame) -> MeshBuffers {
        let (mut vertices, mut indices) = (Vec::new(), Vec::new());
        for mesh in &scene.meshes {
            vertices.extend_from_slice(&mesh.vertices);
            indices.extend_from_slice(&mesh.indices);
        }
        // wgpu refuses empty vertex and index slices; nothing is drawn from these.
        if vertices.is_empty() || indices.is_empty() {
            vertices.push(bytemuck::Zeroable::zeroed());
            indices.push(0);
        }
        let init = |label, contents: &[u8], usage| {
            device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents,
                usage,
            })
        };
        MeshBuffers {
            vertices: init(
                "scene vertices",
                bytemuck::cast_slice(&vertices),
                // Storage too: visibility-buffer passes pull vertices (geometry.wgsl).
                wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::STORAGE,
            ),
            indices: init(
                "scene indices",
                bytemuck::cast_slice(&indices),
                wgpu::BufferUsages::INDEX | wgpu::BufferUsages::STORAGE,
            ),
            data: init(
                "scene meshes",
                frame.bytes(),
                wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
            ),
        }
    }
}

/// `transform` with the camera moved to the origin, computed in f64 and only then cast:
/// vertices near the camera keep their precision even when the world position is large.
pub fn camera_relative(transform: DMat4, camera: DVec3) -> [[f32; 4]; 4] {
    (DMat4::from_translation(-camera) * transform)
        .as_mat4()
        .to_cols_array_2d()
}
