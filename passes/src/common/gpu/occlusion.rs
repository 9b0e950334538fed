//! Occlusion culling's bindings on the device (cluster_occlusion.wgsl's group 3, bound to
//! the tile bins' dispatches that cull clusters): the layout, and each frame's group, the
//! depth pyramid, the list of occluded clusters and, for the first phase, the previous
//! frame's clip space from this frame's camera-relative space.

use glam::DMat4;

use crate::common::occlusion::Phase;
use crate::gpu_scene::view_projection;
use rgraph_scene::{Camera, DepthConvention};

/// occlusion_first.wgsl's FirstPhase: a matrix and a word, padded as a uniform is.
const FIRST_PHASE_BYTES: u64 = 80;

pub(crate) struct OcclusionGroup {
    pub layout: wgpu::BindGroupLayout,
    /// The first phase's uniform and the cameras it was written for.
    first: Option<FirstPhaseCamera>,
}

struct FirstPhaseCamera {
    buffer: wgpu::Buffer,
    /// The frame last recorded, its camera, and the camera of the frame before it.
    cameras: Option<(u64, Camera, Camera)>,
}

impl OcclusionGroup {
    pub fn new(device: &wgpu::Device, phase: Phase) -> OcclusionGroup {
        let entry = |binding, ty| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::COMPUTE,
            ty,
            count: None,
        };
        let mut entries = vec![
            entry(
                1,
                wgpu::BindingType::Texture {
                    sample_type: wgpu::TextureSampleType::Float { filterable: false },
                    view_dimension: wgpu::TextureViewDimension::D2,
                    multisampled: false,
                },
            ),
            entry(
                2,
                wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Storage { read_only: false },
                    has_dynamic_offset: false,
                    min_binding_size: None,
                },
            ),
        ];
        let first = (phase == Phase::First).then(|| {
            entries.push(entry(
                3,
                wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: false,
                    min_binding_size: None,
                },
            ));
            let buffer = device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("occlusion culling: the previous frame's camera"),
                size: FIRST_PHASE_BYTES,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
            FirstPhaseCamera {
                buffer,
                cameras: None,
            }
        });
        let layout = crate::kept::bind_group_layout(device, "occlusion culling", &entries);
        OcclusionGroup { layout, first }
    }

    /// The buffer the group keeps for itself (the first phase's camera), for the pass to
    /// count ([`rgraph_core::gpu::FrameResources::hold`]).
    pub fn buffer(&self) -> Option<&wgpu::Buffer> {
        self.first.as_ref().map(|first| &first.buffer)
    }

    /// This frame's group: `pyramid` (every level) and the list `occluded`; for the first
    /// phase, frame `frame` seen through `camera` at `size`, tested only where `test`
    /// (occlusion culling on, and the pyramid holding the previous frame's depths).
    pub fn group(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        (pyramid, occluded): (&wgpu::TextureView, &wgpu::Buffer),
        (frame, camera, size): (u64, &Camera, (u32, u32)),
        test: bool,
    ) -> wgpu::BindGroup {
        let mut entries = vec![
            wgpu::BindGroupEntry {
                binding: 1,
                resource: wgpu::BindingResource::TextureView(pyramid),
            },
            wgpu::BindGroupEntry {
                binding: 2,
                resource: occluded.as_entire_binding(),
            },
        ];
        if let Some(first) = &mut self.first {
            let clip = first.clip(frame, camera, size);
            let mut bytes = [0u8; FIRST_PHASE_BYTES as usize];
            bytes[..64].copy_from_slice(bytemuck::cast_slice(&clip.to_cols_array()));
            bytes[64..68].copy_from_slice(&u32::from(test).to_le_bytes());
            queue.write_buffer(&first.buffer, 0, &bytes);
            entries.push(wgpu::BindGroupEntry {
                binding: 3,
                resource: first.buffer.as_entire_binding(),
            });
        }
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("occlusion culling"),
            layout: &self.layout,
            entries: &entries,
        })
    }
}

impl FirstPhaseCamera {
    /// The previous frame's clip space (without jitter) from frame `frame`'s
    /// camera-relative space, where the scene's meshes are: the translation from this
    /// camera to the previous one, composed in f64, then the previous camera's rotation and
    /// projection. Meshes are taken to stand still: a moved one is tested where it is now,
    /// which the second phase corrects. The first frame takes its own camera.
    fn clip(&mut self, frame: u64, camera: &Camera, size: (u32, u32)) -> glam::Mat4 {
        let previous = match &self.cameras {
            // Recorded again within one frame: the same previous camera.
            Some((recorded, _, before)) if *recorded == frame => before.clone(),
            Some((_, last, _)) => last.clone(),
            None => camera.clone(),
        };
        let view_proj = view_projection(&previous, size, DepthConvention::ReversedZ).as_dmat4();
        let clip = view_proj * DMat4::from_translation(camera.position - previous.position);
        self.cameras = Some((frame, camera.clone(), previous));
        clip.as_mat4()
    }
}
