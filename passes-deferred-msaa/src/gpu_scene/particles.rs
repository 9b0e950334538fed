//! The scene's particles on the device: one storage buffer of billboards for the
//! `particles` pass's single instanced draw (particles.wgsl's `Particle`), camera-relative
//! like the rest of the scene and ordered for blending.
//!
//! Blended particles come first, farthest first along the view direction (the order
//! seed 001's over-blending needs, and the same in every pass that draws them, so the
//! full- and low-resolution images blend alike), then the emissive ones, whose additive
//! blending needs no order. A pass keeps one [`ParticleBuffer`] per scene upload and calls
//! [`ParticleBuffer::update`] each frame: it rewrites the buffer only when the camera
//! moved since it was written.

use std::ops::Range;

use glam::DVec3;

use crate::scene::{Camera, Particle, Scene, MAX_PARTICLES};

/// `Particle` in particles.wgsl.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct GpuParticle {
    position: [f32; 3],
    size: f32,
    color: [f32; 3],
    alpha: f32,
}

/// A scene's particles in one storage buffer; see the module documentation.
pub struct ParticleBuffer {
    buffer: wgpu::Buffer,
    blended: u32,
    additive: u32,
    /// The camera position and view direction the buffer was written for.
    written_for: Option<(DVec3, DVec3)>,
}

impl ParticleBuffer {
    /// A buffer for `scene`'s particles (one zeroed entry when it has none, as a
    /// binding cannot be empty), written on the first [`update`](Self::update). Loading
    /// refuses more than [`MAX_PARTICLES`]; of a scene built in code without
    /// [`Scene::check_particles`], only the first `MAX_PARTICLES` are drawn, so the
    /// buffer stays within 32 MiB.
    pub fn new(device: &wgpu::Device, scene: &Scene) -> ParticleBuffer {
        let blended = particles(scene).filter(|p| !p.emissive).count();
        let additive = particles(scene).count() - blended;
        let entries = (blended + additive).max(1);
        let buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("particles"),
            size: (entries * std::mem::size_of::<GpuParticle>()) as u64,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        ParticleBuffer {
            buffer,
            // MAX_PARTICLES fits u32.
            blended: blended as u32,
            additive: additive as u32,
            written_for: None,
        }
    }

    /// Writes `scene`'s particles relative to `camera` (the frame's:
    /// [`GpuScene::camera`](super::GpuScene::camera)), sorted, unless the buffer holds them
    /// for that camera pose already.
    pub fn update(&mut self, queue: &wgpu::Queue, scene: &Scene, camera: &Camera) {
        let (eye, forward) = (camera.position, camera.orientation * DVec3::NEG_Z);
        if self.written_for == Some((eye, forward)) || self.blended + self.additive == 0 {
            return;
        }
        let depth = |p: &Particle| (p.position - eye).dot(forward);
        let mut blended: Vec<&Particle> = particles(scene).filter(|p| !p.emissive).collect();
        // Farthest first; stable, so particles at one depth keep the scene's order.
        blended.sort_by(|a, b| depth(b).total_cmp(&depth(a)));
        let gpu: Vec<GpuParticle> = blended
            .into_iter()
            .chain(particles(scene).filter(|p| p.emissive))
            .map(|p| GpuParticle {
                position: (p.position - eye).as_vec3().to_array(),
                size: p.size,
                color: p.color,
                alpha: p.alpha,
            })
            .collect();
        queue.write_buffer(&self.buffer, 0, bytemuck::cast_slice(&gpu));
        self.written_for = Some((eye, forward));
    }

    pub fn buffer(&self) -> &wgpu::Buffer {
        &self.buffer
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

/// The particles the buffer holds: at most [`MAX_PARTICLES`].
fn particles(scene: &Scene) -> impl Iterator<Item = &Particle> {
    scene.particles().take(MAX_PARTICLES)
}
