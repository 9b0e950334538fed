//! The frame's particles on the device: one storage buffer of billboards for the
//! `particles` pass's instanced draws or compute raster (particles.wgsl's `Particle`),
//! camera-relative like the rest of the scene and ordered for blending, and how many of
//! them are blended and drawn in all (`ParticleCounts`, which the compute raster reads),
//! with their bind group.
//!
//! Blended particles come first, farthest first along the view direction (the order
//! seed 001's over-blending needs, and the same in every pass that draws them, so the
//! full- and low-resolution images blend alike), then the emissive ones, whose additive
//! blending needs no order. A pass keeps one [`ParticleBuffer`] per scene upload and calls
//! [`ParticleBuffer::update`] each frame with the frame inputs' emitters: it writes the
//! buffer again only when the camera moved or the emitters are new, and grows it (a new
//! buffer and bind group) when they hold more particles than it has room for.

use std::ops::Range;
use std::sync::Arc;

use glam::DVec3;

use rgraph_scene::{Camera, Particle, ParticleEmitter, MAX_PARTICLES};

/// `Particle` in particles.wgsl.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct GpuParticle {
    position: [f32; 3],
    size: f32,
    color: [f32; 3],
    alpha: f32,
}

/// The frame's particles in one storage buffer; see the module documentation.
pub struct ParticleBuffer {
    layout: wgpu::BindGroupLayout,
    buffer: wgpu::Buffer,
    /// particles.wgsl's `ParticleCounts`.
    counts: wgpu::Buffer,
    group: wgpu::BindGroup,
    /// Particles the buffer has room for.
    capacity: usize,
    blended: u32,
    additive: u32,
    /// The emitters, camera position and view direction the buffer was written for.
    written_for: Option<(Arc<Vec<ParticleEmitter>>, DVec3, DVec3)>,
}

impl ParticleBuffer {
    /// An empty buffer (room for one particle, as a binding cannot be empty) and the bind
    /// group layout of particles.wgsl's group 2.
    pub fn new(device: &wgpu::Device) -> ParticleBuffer {
        let entry = |binding, ty| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::VERTEX | wgpu::ShaderStages::COMPUTE,
            ty: wgpu::BindingType::Buffer {
                ty,
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            count: None,
        };
        let layout = crate::kept::bind_group_layout(
            device,
            "particles",
            &[
                entry(0, wgpu::BufferBindingType::Storage { read_only: true }),
                entry(1, wgpu::BufferBindingType::Uniform),
            ],
        );
        let counts = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("particle counts"),
            size: 16,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let (buffer, group) = storage(device, &layout, &counts, 1);
        ParticleBuffer {
            layout,
            buffer,
            counts,
            group,
            capacity: 1,
            blended: 0,
            additive: 0,
            written_for: None,
        }
    }

    /// Writes the particles of `emitters` relative to `camera` (the frame's), sorted,
    /// unless the buffer holds them for that camera pose already. Only the first
    /// [`MAX_PARTICLES`] are drawn (`Host::set_frame` and scene loading refuse more), so
    /// the buffer stays within 32 MiB.
    pub fn update(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        emitters: &Arc<Vec<ParticleEmitter>>,
        camera: &Camera,
    ) {
        let (eye, forward) = (camera.position, camera.orientation * DVec3::NEG_Z);
        if let Some((written, e, f)) = &self.written_for {
            if Arc::ptr_eq(written, emitters) && (*e, *f) == (eye, forward) {
                return;
            }
        }
        let all = || {
            emitters
                .iter()
                .flat_map(|e| e.particles.iter())
                .take(MAX_PARTICLES)
        };
        let depth = |p: &Particle| (p.position - eye).dot(forward);
        let mut blended: Vec<&Particle> = all().filter(|p| !p.emissive).collect();
        // Farthest first; stable, so particles at one depth keep the emitters' order.
        blended.sort_by(|a, b| depth(b).total_cmp(&depth(a)));
        self.blended = blended.len() as u32;
        let gpu: Vec<GpuParticle> = blended
            .into_iter()
            .chain(all().filter(|p| p.emissive))
            .map(|p| GpuParticle {
                position: (p.position - eye).as_vec3().to_array(),
                size: p.size,
                color: p.color,
                alpha: p.alpha,
            })
            .collect();
        // MAX_PARTICLES fits u32.
        self.additive = (gpu.len() - self.blended as usize) as u32;
        if gpu.len() > self.capacity {
            // Twice what is needed, so a system that grows a little each frame does not
            // make a buffer each frame.
            self.capacity = (2 * gpu.len()).min(MAX_PARTICLES);
            (self.buffer, self.group) = storage(device, &self.layout, &self.counts, self.capacity);
        }
        queue.write_buffer(&self.buffer, 0, bytemuck::cast_slice(&gpu));
        let counts = [self.blended, self.blended + self.additive, 0, 0];
        queue.write_buffer(&self.counts, 0, bytemuck::cast_slice(&counts));
        self.written_for = Some((emitters.clone(), eye, forward));
    }

    /// The layout of [`group`](Self::group), for the pass's pipeline layout.
    pub fn layout(&self) -> &wgpu::BindGroupLayout {
        &self.layout
    }

    /// particles.wgsl's group 2: the buffer as [`update`](Self::update) last made it.
    pub fn group(&self) -> &wgpu::BindGroup {
        &self.group
    }

    /// The instances of the blended particles.
    pub fn blended(&self) -> Range<u32> {
        0..self.blended
    }

    /// The instances of the emissive particles.
    pub fn additive(&self) -> Range<u32> {
        self.blended..self.blended + self.additive
    }
}

/// A storage buffer with room for `particles` and its bind group, with `counts`.
fn storage(
    device: &wgpu::Device,
    layout: &wgpu::BindGroupLayout,
    counts: &wgpu::Buffer,
    particles: usize,
) -> (wgpu::Buffer, wgpu::BindGroup) {
    let buffer = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("particles"),
        size: (particles * std::mem::size_of::<GpuParticle>()) as u64,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("particles"),
        layout,
        entries: &[
            wgpu::BindGroupEntry {
                binding: 0,
                resource: buffer.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: counts.as_entire_binding(),
            },
        ],
    });
    (buffer, group)
}
