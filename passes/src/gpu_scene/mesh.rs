//! Scene geometry on the device: every mesh's vertices and indices in one buffer each (the
//! vertices meshes share held once, see shared_geometry.rs), and per-mesh data (camera-relative model matrix, normal matrix, material) in a storage
//! buffer the G-buffer vertex shader indexes with the instance index.

use std::sync::Arc;

use glam::{DMat3, DMat4, DVec3, Vec3};
use wgpu::util::DeviceExt;

use super::shared_geometry::GeometryLayout;
use super::view_culling::ClusterBoxes;
use rgraph_scene::{Aabb, Cluster, ClusteredMesh, Scene, Vertex};

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
    /// The mesh's range in the scene's shared index buffer.
    pub indices: std::ops::Range<u32>,
    /// Added to each index: where the mesh's vertices start in the shared vertex buffer.
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
    /// Each mesh's triangles in cluster order (rgraph_scene::cluster): a triangle's
    /// position here, its ID, is not its position in `Mesh::indices`.
    pub indices: wgpu::Buffer,
    /// Each distinct geometry's clusters, ranges of its triangles from a placing mesh's
    /// first in `indices`, and their boxes, for the views that draw only what they see.
    shapes: Vec<(Vec<Cluster>, ClusterBoxes)>,
    /// Each mesh's geometry in `shapes`.
    shape_of: Vec<u32>,
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
    /// Where each mesh's geometry lies in the scene's buffers: the first frame's, kept.
    pub layout: Arc<GeometryLayout>,
}

impl MeshFrame {
    /// The meshes of `scene` placed by `transforms` (one per mesh) and seen from `eye`,
    /// the deformed ones within their object-space box of `deformed` (one per mesh, or
    /// none for a scene without deformations; see deform.rs). `previous` is the frame
    /// before, whose bounds are reused for the undeformed meshes `transforms` does not
    /// move.
    pub fn new(
        scene: &Scene,
        (transforms, deformed): (&[DMat4], &[Option<Aabb>]),
        eye: DVec3,
        previous: Option<(&MeshFrame, &[DMat4])>,
    ) -> MeshFrame {
        let layout = previous.map_or_else(
            || Arc::new(GeometryLayout::new(scene)),
            |(frame, _)| frame.layout.clone(),
        );
        let mut frame = MeshFrame {
            data: Vec::new(),
            draws: Vec::new(),
            world_bounds: Vec::new(),
            layout: layout.clone(),
        };
        let placed = scene.meshes.iter().zip(&layout.placements);
        for (((mesh, placement), &transform), instance) in placed.zip(transforms).zip(0u32..) {
            let object_box = deformed.get(instance as usize).copied().flatten();
            let kept = previous
                .filter(|_| object_box.is_none())
                .and_then(|(frame, transforms)| {
                    (transforms.get(instance as usize) == Some(&transform))
                        .then(|| frame.world_bounds[instance as usize])
                });
            let world_bounds = kept.unwrap_or_else(|| {
                let place = |p: DVec3| transform.transform_point3(p);
                let placed = match object_box {
                    Some(b) => Some(b.transformed(&transform)),
                    None => Aabb::from_points(
                        (mesh.vertices.iter())
                            .map(|v| place(Vec3::from_array(v.position).as_dvec3())),
                    ),
                };
                placed.unwrap_or_else(|| {
                    let origin = transform.w_axis.truncate();
                    Aabb {
                        min: origin,
                        max: origin,
                    }
                })
            });
            frame.world_bounds.push(world_bounds);
            let first_index = placement.first_index;
            frame.draws.push(MeshDraw {
                indices: first_index..first_index + mesh.indices.len() as u32,
                base_vertex: placement.base_vertex,
                instance,
                material: mesh.material,
                center: world_bounds.center() - eye,
                bounds: Aabb {
                    min: world_bounds.min - eye,
                    max: world_bounds.max - eye,
                },
            });
            // Mesh::normal_matrix of the placed mesh.
            let normal = DMat3::from_mat4(transform).inverse().transpose().as_mat3();
            frame.data.push(MeshData {
                model: camera_relative(transform, eye),
                normal_matrix: [normal.x_axis, normal.y_axis, normal.z_axis]
                    .map(|c| c.extend(0.0).to_array()),
                material: mesh.material as u32,
                first_index,
                base_vertex: placement.base_vertex,
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

    /// The model matrix of `Scene::meshes[instance]`, camera-relative, as the shaders
    /// have it.
    pub fn model(&self, instance: u32) -> DMat4 {
        glam::Mat4::from_cols_array_2d(&self.data[instance as usize].model).as_dmat4()
    }

    /// The data buffer's contents.
    pub fn bytes(&self) -> &[u8] {
        bytemuck::cast_slice(&self.data)
    }
}

impl MeshBuffers {
    /// Uploads `scene`'s geometry as `frame`'s layout places it, and `frame`'s per-mesh
    /// data. The geometry goes up array by array in slices (see [`UPLOAD_SLICE_BYTES`]),
    /// never gathered into one copy first; the indices in cluster order are a copy of each
    /// distinct geometry's, held until they are up. An error, before anything is
    /// allocated, when the vertices or indices are more than the device holds in one
    /// buffer.
    pub fn new(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        scene: &Scene,
        frame: &MeshFrame,
    ) -> Result<MeshBuffers, String> {
        let layout = &frame.layout;
        let max = device.limits().max_buffer_size;
        for (what, bytes) in layout.buffer_bytes(scene) {
            if bytes > max {
                return Err(format!(
                    "the scene's {what} take {bytes} bytes, more than the {max} bytes this \
                     device holds in one buffer (max_buffer_size): no pipeline can draw them \
                     on it"
                ));
            }
        }
        let upload = Upload { device, queue };
        // Clustered here, from the meshes as they are now, so that the clusters cannot
        // go stale: every pipeline draws the one index buffer, in cluster order.
        let clustered: Vec<ClusteredMesh> = (layout.shape_owners.iter())
            .map(|&mesh| rgraph_scene::cluster(&scene.meshes[mesh]))
            .collect();
        let placements = layout.placements.iter();
        Ok(MeshBuffers {
            // Storage too: visibility-buffer passes pull vertices (geometry.wgsl).
            vertices: upload.gathered(
                "scene vertices",
                (layout.vertex_owners.iter()).map(|&mesh| scene.meshes[mesh].vertices.as_slice()),
                wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::STORAGE,
            ),
            indices: upload.gathered(
                "scene indices",
                placements.map(|p| clustered[p.shape as usize].indices.as_slice()),
                wgpu::BufferUsages::INDEX | wgpu::BufferUsages::STORAGE,
            ),
            shape_of: layout.placements.iter().map(|p| p.shape).collect(),
            shapes: (clustered.into_iter())
                .map(|m| {
                    let boxes = ClusterBoxes::new(&m.clusters);
                    (m.clusters, boxes)
                })
                .collect(),
            data: device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("scene meshes"),
                contents: frame.bytes(),
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
            }),
        })
    }
}

impl MeshBuffers {
    /// The clusters of `Scene::meshes[mesh]`, ranges of its triangles from its first.
    pub fn clusters(&self, mesh: usize) -> &[Cluster] {
        &self.shapes[self.shape_of[mesh] as usize].0
    }

    /// The boxes of `Scene::meshes[mesh]`'s clusters, in its own space.
    pub fn cluster_boxes(&self, mesh: usize) -> &ClusterBoxes {
        &self.shapes[self.shape_of[mesh] as usize].1
    }
}

/// The most geometry staged at once. Each slice is written, submitted and waited for
/// before the next, so the upload holds one slice beside the scene and the device's
/// buffers. Gathered into one vector and mapped at creation, the geometry of a 10M-triangle
/// flat-shaded scene (1.8 GB) was held three times over: the scene's, the gathered copy
/// (or the mapping's staging buffer) and the device's; on a CPU adapter all in host memory.
const UPLOAD_SLICE_BYTES: u64 = 64 << 20;

struct Upload<'a> {
    device: &'a wgpu::Device,
    queue: &'a wgpu::Queue,
}

impl Upload<'_> {
    /// A buffer holding `parts` one after another, uploaded in slices. wgpu refuses empty
    /// vertex and index buffers (and zero-sized storage bindings): without parts it holds
    /// one element, zeroed as every new buffer is, from which nothing is drawn.
    fn gathered<'p, T: bytemuck::Pod>(
        &self,
        label: &str,
        parts: impl Iterator<Item = &'p [T]> + Clone,
        usage: wgpu::BufferUsages,
    ) -> wgpu::Buffer {
        let element = std::mem::size_of::<T>() as u64;
        let bytes: u64 = parts.clone().map(|p| p.len() as u64 * element).sum();
        let buffer = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(label),
            size: bytes
                .max(element)
                .next_multiple_of(wgpu::COPY_BUFFER_ALIGNMENT),
            usage: usage | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        // Whole elements per slice; vertices and indices are multiples of 4 bytes, as
        // buffer writes must be.
        let per_slice = (UPLOAD_SLICE_BYTES / element).max(1) as usize;
        let (mut offset, mut staged) = (0, 0);
        for slice in parts.flat_map(|part| part.chunks(per_slice)) {
            let slice: &[u8] = bytemuck::cast_slice(slice);
            self.queue.write_buffer(&buffer, offset, slice);
            offset += slice.len() as u64;
            staged += slice.len() as u64;
            if staged >= UPLOAD_SLICE_BYTES {
                self.flush();
                staged = 0;
            }
        }
        buffer
    }

    /// Runs the staged writes and frees their staging memory. A device lost meanwhile is
    /// reported where the frame is submitted.
    fn flush(&self) {
        self.queue.submit([]);
        let _ = self.device.poll(wgpu::PollType::wait_indefinitely());
    }
}

/// `transform` with the camera moved to the origin, computed in f64 and only then cast:
/// vertices near the camera keep their precision even when the world position is large.
pub fn camera_relative(transform: DMat4, camera: DVec3) -> [[f32; 4]; 4] {
    (DMat4::from_translation(-camera) * transform)
        .as_mat4()
        .to_cols_array_2d()
}
