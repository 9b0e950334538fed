//! Skinning and morphing on the device (deform.wgsl), done where the scene's frame inputs
//! are uploaded: when a frame's joints, morph weights or deformed meshes' transforms
//! change, one compute dispatch writes the deformed meshes' vertices over their rest
//! ones in the scene's vertex buffer, submitted before the frame's passes, so that every
//! pass reading the buffer (hardware and compute rasters, G-buffer, forward, shadow maps,
//! visibility shading, motion vectors) draws the deformed shape without knowing of it.
//!
//! Each dispatch first keeps the positions it replaces ([`Deformer::previous`]): where the
//! last pose had the vertices, which motion vectors move a deformed surface from.
//!
//! A scene without deformations ([`rgraph_scene::Scene::deformations`] empty) gets no
//! [`Deformer`]: no buffer, no pipeline, no dispatch. One with them keeps, per deformed
//! vertex, its rest vertex (56 bytes) and its influence (32 bytes: four joints and
//! weights), 32 bytes more for a vertex of a mesh with eight influences (glTF's JOINTS_1
//! and WEIGHTS_1, an entry of its own that the first one points to, so that meshes of four
//! pay nothing for it), per morph target and vertex 36 bytes of offsets, per vertex from
//! the first deformed mesh's to the last's its previous position (12 bytes), and per frame
//! 64 bytes per joint of each skinned mesh and 4 per morph weight.

use glam::DMat4;
use wgpu::util::DeviceExt;

use super::shared_geometry::GeometryLayout;
use crate::host::FrameInputs;
use rgraph_scene::{joints_in_object_space, Aabb, Influences, Reach, Scene, Vertex};

/// deform.wgsl's `Influence`.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct Influence {
    joints: [u32; 2],
    deformation: u32,
    second: u32,
    weights: [f32; 4],
}

impl Influence {
    /// Vertex `vertex`'s joints and weights of `set` (none without a skin) in
    /// `deformation`, whose fifth to eighth are at `second` (0 for none).
    fn new(set: Option<&Influences>, vertex: usize, deformation: u32, second: u32) -> Influence {
        let ids = set.map_or([0; 4], |s| s.joints[vertex]).map(u32::from);
        Influence {
            joints: [ids[0] | ids[1] << 16, ids[2] | ids[3] << 16],
            deformation,
            second,
            weights: set.map_or([0.0; 4], |s| s.weights[vertex]),
        }
    }
}

/// deform.wgsl's `Deformation`.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct DeformationData {
    first_vertex: u32,
    base_word: u32,
    vertex_count: u32,
    first_joint: u32,
    first_offset: u32,
    first_weight: u32,
    targets: u32,
    skinned: u32,
    /// Its first vertex in `previous`.
    first_previous: u32,
}

/// The workgroup size of `cs_deform`.
const GROUP: u32 = 64;
/// The most workgroups along one dimension of a dispatch (WebGPU's default limit).
const MAX_GROUPS: u32 = 65535;
/// u32 words per [`Vertex`].
const WORDS: u64 = (std::mem::size_of::<Vertex>() / 4) as u64;

/// One frame's deformation on the CPU: what the joints and weights buffers hold, and
/// where each deformed mesh may be.
#[derive(Clone, PartialEq)]
pub(super) struct DeformFrame {
    /// Each skinned deformation's joints in its mesh's object space, one after another.
    joints: Vec<[[f32; 4]; 4]>,
    /// Each morphed deformation's weights, one after another.
    weights: Vec<f32>,
    /// Per mesh of the scene, its object-space box this frame if it is deformed (its
    /// [`Reach`]); empty for a scene without deformations.
    pub boxes: Vec<Option<Aabb>>,
}

impl DeformFrame {
    /// The deformations of `scene` posed by `inputs`, bounded by `reaches` (one per
    /// deformation, [`reaches`]).
    pub fn new(scene: &Scene, inputs: &FrameInputs, reaches: &[Option<Reach>]) -> DeformFrame {
        let mut frame = DeformFrame {
            joints: Vec::new(),
            weights: Vec::new(),
            boxes: Vec::new(),
        };
        if scene.deformations.is_empty() {
            return frame;
        }
        frame.boxes = vec![None; scene.meshes.len()];
        let posed = (scene.deformations.iter().zip(reaches)).zip(&inputs.morph_weights);
        for ((deformation, reach), weights) in posed {
            let transform = inputs.transforms[deformation.mesh];
            let joints: Vec<DMat4> = match &deformation.skin {
                Some(skin) => joints_in_object_space(transform, &inputs.skins[skin.skin]),
                None => Vec::new(),
            };
            frame.boxes[deformation.mesh] = reach.as_ref().map(|r| r.object_box(&joints, weights));
            let as_f32 = |m: &DMat4| m.as_mat4().to_cols_array_2d();
            frame.joints.extend(joints.iter().map(as_f32));
            frame.weights.extend_from_slice(weights);
        }
        frame
    }
}

/// Each deformation's [`Reach`], in the order of `scene.deformations`.
pub(super) fn reaches(scene: &Scene) -> Vec<Option<Reach>> {
    (scene.deformations.iter())
        .map(|d| Reach::new(d, &scene.meshes[d.mesh].vertices))
        .collect()
}

/// The deformation pass's device objects, made with the scene's upload when it has
/// deformed meshes.
pub(super) struct Deformer {
    pipeline: wgpu::ComputePipeline,
    group: wgpu::BindGroup,
    joints: wgpu::Buffer,
    weights: wgpu::Buffer,
    /// Deformed vertices: one invocation each.
    vertex_count: u32,
    previous: PreviousPositions,
}

/// Where the scene's vertices were before the last deformation, as the dispatch found
/// them before writing the pose over them.
pub struct PreviousPositions {
    /// The object-space positions, 3 f32 each, of vertices `first..end`.
    pub buffer: wgpu::Buffer,
    /// The scene's first vertex held: the first deformed mesh's first.
    pub first: u32,
    /// The vertex after the last held: the last deformed mesh's last, plus one. The
    /// meshes between that do not deform hold their rest positions throughout.
    pub end: u32,
}

impl Deformer {
    /// The pass for `scene`'s deformations over `vertices`, the scene's vertex buffer laid
    /// out as `layout` says (a deforming scene shares no vertices, so each mesh's follow
    /// the ones before it), or `None` when nothing deforms.
    pub fn new(
        device: &wgpu::Device,
        scene: &Scene,
        (vertices, layout): (&wgpu::Buffer, &GeometryLayout),
    ) -> Option<Deformer> {
        if scene.deformations.is_empty() {
            return None;
        }
        // Where each mesh's vertices start, and after the last mesh where it ends.
        let last = scene.meshes.len() - 1;
        let first_vertex: Vec<u64> = (layout.placements.iter())
            .map(|p| p.base_vertex as u64)
            .chain([layout.placements[last].base_vertex as u64
                + scene.meshes[last].vertices.len() as u64])
            .collect();
        // The vertex buffer is bound from the first deformed vertex (rounded down to the
        // storage offset alignment), so a scene larger than one storage binding can
        // still deform a few meshes.
        let alignment = u64::from(device.limits().min_storage_buffer_offset_alignment);
        let first_mesh = scene.deformations[0].mesh;
        let last_mesh = scene.deformations.last().map_or(0, |d| d.mesh);
        let in_range = &scene.meshes[first_mesh..=last_mesh];
        let previous: Vec<[f32; 3]> = (in_range.iter())
            .flat_map(|mesh| mesh.vertices.iter().map(|v| v.position))
            .collect();
        let start = (first_vertex[first_mesh] * WORDS * 4) / alignment * alignment;
        let end = first_vertex[last_mesh + 1] * WORDS * 4;
        let (mut rest, mut influences, mut data, mut offsets) =
            (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        // Second sets (JOINTS_1) follow the deformed vertices' entries in `influences`.
        let deformed: usize = (scene.deformations.iter())
            .map(|d| scene.meshes[d.mesh].vertices.len())
            .sum();
        let mut seconds = Vec::new();
        let (mut joints, mut weights) = (0u32, 0u32);
        for (index, deformation) in scene.deformations.iter().enumerate() {
            let mesh = &scene.meshes[deformation.mesh];
            let morph = deformation.morph.as_ref();
            let targets = morph.map_or(0, |m| m.targets.len() as u32);
            data.push(DeformationData {
                first_vertex: influences.len() as u32,
                base_word: ((first_vertex[deformation.mesh] * WORDS * 4 - start) / 4) as u32,
                vertex_count: mesh.vertices.len() as u32,
                first_joint: joints,
                first_offset: (offsets.len() / 9) as u32,
                first_weight: weights,
                targets,
                skinned: u32::from(deformation.skin.is_some()),
                first_previous: (first_vertex[deformation.mesh] - first_vertex[first_mesh]) as u32,
            });
            rest.extend_from_slice(&mesh.vertices);
            let skin = deformation.skin.as_ref();
            let second = skin.and_then(|s| s.second.as_ref());
            influences.extend((0..mesh.vertices.len()).map(|v| {
                let at = second.map_or(0, |_| (deformed + seconds.len() + v) as u32);
                Influence::new(skin.map(|s| &s.first), v, index as u32, at)
            }));
            seconds.extend((second.iter()).flat_map(|set| {
                (0..mesh.vertices.len()).map(|v| Influence::new(Some(set), v, index as u32, 0))
            }));
            for target in morph.iter().flat_map(|m| &m.targets) {
                let at = |list: &[[f32; 3]], v: usize| list.get(v).copied().unwrap_or([0.0; 3]);
                offsets.extend((0..mesh.vertices.len()).flat_map(|v| {
                    [
                        at(&target.positions, v),
                        at(&target.normals, v),
                        at(&target.tangents, v),
                    ]
                    .into_iter()
                    .flatten()
                }));
            }
            joints += skin.map_or(0, |s| scene.skins[s.skin].joints.len() as u32);
            weights += targets;
        }
        influences.extend(seconds);
        let storage = |label, contents: &[u8], usage| {
            // wgpu refuses storage bindings smaller than one element: an empty list holds
            // one zeroed (64 bytes: a joint, the largest element here).
            let padded = [0u8; 64];
            let contents = if contents.is_empty() {
                &padded[..]
            } else {
                contents
            };
            device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents,
                usage: wgpu::BufferUsages::STORAGE | usage,
            })
        };
        let constant = wgpu::BufferUsages::empty();
        let rest = storage(
            "deform rest vertices",
            bytemuck::cast_slice(&rest),
            constant,
        );
        let influences_buffer = storage(
            "deform influences",
            bytemuck::cast_slice(&influences),
            constant,
        );
        let data = storage("deformations", bytemuck::cast_slice(&data), constant);
        let offsets = storage(
            "deform morph offsets",
            bytemuck::cast_slice(&offsets),
            constant,
        );
        let previous_buffer = storage(
            "deformed vertices' previous positions",
            bytemuck::cast_slice(&previous),
            constant,
        );
        let per_frame = |label, bytes: u64| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: bytes.max(64),
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            })
        };
        let joints = per_frame("deform joints", u64::from(joints) * 64);
        let weights = per_frame("deform weights", u64::from(weights) * 4);
        let module = crate::kept::module(device, "deform", include_str!("../wgsl/deform.wgsl"));
        let pipeline = crate::kept::compute_pipeline(
            device,
            &wgpu::ComputePipelineDescriptor {
                label: Some("deform"),
                layout: None,
                module: &module,
                entry_point: Some("cs_deform"),
                compilation_options: Default::default(),
                cache: None,
            },
        );
        fn whole(buffer: &wgpu::Buffer) -> wgpu::BindingResource<'_> {
            buffer.as_entire_binding()
        }
        let bound = wgpu::BindingResource::Buffer(wgpu::BufferBinding {
            buffer: vertices,
            offset: start,
            size: wgpu::BufferSize::new(end - start),
        });
        let resources = [
            bound,
            whole(&rest),
            whole(&influences_buffer),
            whole(&data),
            whole(&offsets),
            whole(&joints),
            whole(&weights),
            whole(&previous_buffer),
        ];
        let entries: Vec<wgpu::BindGroupEntry> = (resources.into_iter().zip(0..))
            .map(|(resource, binding)| wgpu::BindGroupEntry { binding, resource })
            .collect();
        let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("deform"),
            layout: &pipeline.get_bind_group_layout(0),
            entries: &entries,
        });
        Some(Deformer {
            pipeline,
            group,
            joints,
            weights,
            vertex_count: deformed as u32,
            previous: PreviousPositions {
                buffer: previous_buffer,
                first: first_vertex[first_mesh] as u32,
                end: first_vertex[last_mesh + 1] as u32,
            },
        })
    }

    /// The positions the last dispatch replaced.
    pub fn previous(&self) -> &PreviousPositions {
        &self.previous
    }

    /// Writes `frame`'s joints and weights and deforms the vertices, in a submission of
    /// its own: it lands before the frame's, whose passes then read the deformed
    /// vertices.
    pub fn run(&self, device: &wgpu::Device, queue: &wgpu::Queue, frame: &DeformFrame) {
        if !frame.joints.is_empty() {
            queue.write_buffer(&self.joints, 0, bytemuck::cast_slice(&frame.joints));
        }
        if !frame.weights.is_empty() {
            queue.write_buffer(&self.weights, 0, bytemuck::cast_slice(&frame.weights));
        }
        let groups = self.vertex_count.div_ceil(GROUP);
        let (x, y) = (groups.min(MAX_GROUPS), groups.div_ceil(MAX_GROUPS));
        let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("deform"),
        });
        {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("deform"),
                timestamp_writes: None,
            });
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, &self.group, &[]);
            pass.dispatch_workgroups(x, y, 1);
        }
        queue.submit([encoder.finish()]);
    }
}
