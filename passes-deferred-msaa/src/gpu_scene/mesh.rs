//! Scene geometry on the device: every mesh's vertices and indices in one buffer each, and
//! per-mesh data (camera-relative model matrix, normal matrix, material) in a storage
//! buffer the G-buffer vertex shader indexes with the instance index.

use glam::{DMat4, DVec3};
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
    _pad: [u32; 3],
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
    /// the camera, for drawing blended meshes back to front.
    pub center: DVec3,
}

pub(super) struct MeshBuffers {
    pub vertices: wgpu::Buffer,
    pub indices: wgpu::Buffer,
    pub data: wgpu::Buffer,
    pub draws: Vec<MeshDraw>,
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

impl MeshBuffers {
    pub fn new(device: &wgpu::Device, scene: &Scene) -> MeshBuffers {
        let (mut vertices, mut indices, mut data, mut draws) =
            (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        for (mesh, instance) in scene.meshes.iter().zip(0u32..) {
            let first = indices.len() as u32;
            draws.push(MeshDraw {
                indices: first..first + mesh.indices.len() as u32,
                base_vertex: vertices.len() as i32,
                instance,
                material: mesh.material,
                center: Aabb::from_points(mesh.world_positions())
                    .map_or(mesh.transform.w_axis.truncate(), |b| b.center())
                    - scene.camera.position,
            });
            vertices.extend_from_slice(&mesh.vertices);
            indices.extend_from_slice(&mesh.indices);
            let normal = mesh.normal_matrix().as_mat3();
            data.push(MeshData {
                model: camera_relative(mesh.transform, scene.camera.position),
                normal_matrix: [normal.x_axis, normal.y_axis, normal.z_axis]
                    .map(|c| c.extend(0.0).to_array()),
                material: mesh.material as u32,
                _pad: [0; 3],
            });
        }
        // A scene without meshes (a glTF scene listing no nodes) still binds these buffers:
        // wgpu refuses empty slices and zero-sized storage bindings, and nothing is drawn.
        if draws.is_empty() {
            vertices.push(bytemuck::Zeroable::zeroed());
            indices.push(0);
            data.push(bytemuck::Zeroable::zeroed());
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
                wgpu::BufferUsages::VERTEX,
            ),
            indices: init(
                "scene indices",
                bytemuck::cast_slice(&indices),
                wgpu::BufferUsages::INDEX,
            ),
            data: init(
                "scene meshes",
                bytemuck::cast_slice(&data),
                wgpu::BufferUsages::STORAGE,
            ),
            draws,
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
