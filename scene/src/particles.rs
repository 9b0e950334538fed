//! Particle emitters: camera-facing billboards of smoke, dust or fire that the `particles`
//! pass draws after the opaque scene is lit (seed 001, passes/particles.rs).
//!
//! An emitter is a named set of particles at the positions an engine's simulation (or a
//! built-in scene) gave them; the passes draw a snapshot of them, the blended ones back
//! to front from the camera and the emissive ones added after. A particle is a disc of
//! `size` world units across facing the camera, whose opacity falls off from its centre
//! (the procedural soft texture of particles.wgsl).

use glam::{DVec3, DVec4};

use super::{Camera, DepthConvention, SceneError, MAX_COORDINATE};

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
    /// Its particles, in any order: the passes sort the blended ones back to front.
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

/// Fails when `emitters` (of scene `scene`) hold more than [`MAX_PARTICLES`] particles,
/// or a particle that cannot be drawn ([`Particle::invalid`], or farther from the origin
/// than [`MAX_COORDINATE`]), naming the emitter and the particle.
pub fn check_emitters(scene: &str, emitters: &[ParticleEmitter]) -> Result<(), SceneError> {
    let count: usize = emitters.iter().map(|e| e.particles.len()).sum();
    if count > MAX_PARTICLES {
        return Err(SceneError::TooManyParticles {
            scene: scene.to_owned(),
            count,
            max: MAX_PARTICLES,
        });
    }
    for emitter in emitters {
        for (index, particle) in emitter.particles.iter().enumerate() {
            if let Some(reason) = particle.invalid() {
                return Err(SceneError::InvalidParticle {
                    scene: scene.to_owned(),
                    emitter: emitter.name.clone(),
                    index,
                    reason,
                });
            }
            let extent = particle.position.abs().max_element();
            if extent > MAX_COORDINATE {
                return Err(SceneError::TooFar {
                    scene: scene.to_owned(),
                    what: format!("particle {index} of emitter \"{}\"", emitter.name),
                    value: extent,
                    max: MAX_COORDINATE,
                });
            }
        }
    }
    Ok(())
}

/// How many pixels the billboards of `particles` cover on a target of `size` seen by
/// `camera`, overlaps counted as often as they overlap: the fragments a particle pass
/// shades (seed 001's "particle pixels"). Each billboard is the square of its diameter
/// facing the camera, cut to the target; one reaching behind the near plane is left out.
pub fn billboard_pixels<'a>(
    particles: impl IntoIterator<Item = &'a Particle>,
    camera: &Camera,
    size: (u32, u32),
) -> f64 {
    let (width, height) = (f64::from(size.0), f64::from(size.1));
    let aspect = (width / height.max(1.0)) as f32;
    let projection = camera
        .projection_matrix(aspect, DepthConvention::Standard)
        .as_dmat4();
    let view = camera.view_matrix();
    let ndc = |v: DVec4| (v.w > 0.0).then(|| v.truncate().truncate() / v.w);
    particles
        .into_iter()
        .filter_map(|p| {
            let centre = view * p.position.extend(1.0);
            let radius = 0.5 * f64::from(p.size);
            // Wholly in front of the camera (view space looks down -z).
            if centre.z + radius >= 0.0 {
                return None;
            }
            let middle = ndc(projection * centre)?;
            let top = ndc(projection * (centre + DVec4::new(0.0, radius, 0.0, 0.0)))?;
            let half = (top.y - middle.y).abs() * 0.5 * height;
            let (x, y) = (
                (middle.x + 1.0) * 0.5 * width,
                (1.0 - middle.y) * 0.5 * height,
            );
            let cover = |centre: f64, extent: f64| {
                ((centre + half).min(extent) - (centre - half).max(0.0)).max(0.0)
            };
            Some(cover(x, width) * cover(y, height))
        })
        .sum()
}
