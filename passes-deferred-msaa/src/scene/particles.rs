//! Particle emitters: camera-facing billboards of smoke, dust or fire that the `particles`
//! pass draws after the opaque scene is lit (seed 001, passes/particles.rs).
//!
//! An emitter is a named set of particles at the positions an engine's simulation (or a
//! built-in scene) gave them; the passes draw a snapshot of them, the blended ones back
//! to front from the camera and the emissive ones added after. A particle is a disc of
//! `size` world units across facing the camera, whose opacity falls off from its centre
//! (the procedural soft texture of particles.wgsl).

use glam::DVec3;

/// The most particles a scene may hold over all its emitters: 32 bytes each on the device,
/// so 32 MiB, and one instance each in a single draw.
pub const MAX_PARTICLES: usize = 1 << 20;

/// One billboard.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Particle {
    /// Its centre, in world space.
    pub position: DVec3,
    /// Its diameter in world units: finite and positive.
    pub size: f32,
    /// Linear RGB. A blended particle's is its albedo, lit by the scene's ambient
    /// radiance; an emissive particle's is the radiance it adds (any finite value ≥ 0).
    pub color: [f32; 3],
    /// Opacity at its centre, 0 to 1. An emissive particle's scales what it adds.
    pub alpha: f32,
    /// Added to what is behind it (fire, sparks) rather than blended over it (smoke).
    pub emissive: bool,
}

/// A named group of particles: what an engine's particle system hands the renderer.
#[derive(Clone, Debug, PartialEq)]
pub struct ParticleEmitter {
    /// Names the emitter in errors.
    pub name: String,
    pub particles: Vec<Particle>,
}

impl Particle {
    /// Why this particle cannot be drawn, if it cannot: a position or size that is not
    /// finite, a size that is not positive, an alpha outside 0 to 1, or a colour that
    /// is negative or not finite.
    pub fn invalid(&self) -> Option<String> {
        if !self.position.is_finite() {
            return Some(format!("position {} is not finite", self.position));
        }
        if !(self.size.is_finite() && self.size > 0.0) {
            return Some(format!("size {} is not finite and positive", self.size));
        }
        if !(0.0..=1.0).contains(&self.alpha) {
            return Some(format!("alpha {} is not within 0 to 1", self.alpha));
        }
        if self.color.iter().any(|c| !(c.is_finite() && *c >= 0.0)) {
            return Some(format!(
                "color {:?} is not finite and non-negative",
                self.color
            ));
        }
        None
    }
}
