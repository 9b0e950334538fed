//! `builtin:smoke`: smoke and fire over `builtin:dense`, the overdraw case off-screen
//! particles exist for (seed 001).
//!
//! - The geometry, lights and camera of [`super::dense`], ambient raised to 0.25 (the
//!   smoke is lit by ambient only: see passes/particles.rs).
//! - Emitter "smoke": `count - count / 8` blended particles (3,500 of the default 4,000),
//!   their centres in a column that widens upward over the solids: height y in [0, 4),
//!   radius from the y axis growing from 2 at the ground to 7 at the top (uniform over the
//!   disc), diameters from 0.5 to 1.5 times `size`, grey albedo 0.35 to 0.75, alpha 0.05
//!   to 0.25. Seen from the camera they fill most of the frame, hundreds deep.
//! - Emitter "fire": `count / 8` emissive particles near the ground (y in [0, 1), radius up
//!   to 1.2), diameters 0.3 to 0.8 times `size`, orange radiance 2 to 6, alpha 0.2 to 0.6.
//! - `size` is the nominal diameter in centimetres (default 120: 1.2 units), `seed` seeds
//!   [`Pcg32`] (default 1), so each (count, size, seed) is one fixed scene.
//! - `extent` scales the whole effect about the origin, positions and diameters, in
//!   percent (default 100): how much of the frame it fills without moving the camera,
//!   as the seed moved away from its effect to shrink it on screen (Table 23-3). The
//!   same particles in the same order at every extent.

use std::f32::consts::TAU;

use glam::DVec3;

use super::params::{BuiltinParam, Params};
use super::rng::Pcg32;
use crate::builder::SceneBuilder;
use crate::{Particle, ParticleEmitter, SceneError, MAX_PARTICLES};

/// The parameters `builtin:smoke?...` takes.
pub(super) const PARAMS: &[BuiltinParam] = &[
    BuiltinParam {
        key: "count",
        meaning:
            "total number of particles, 7/8 smoke and 1/8 fire (default 4000, at most 1048576)",
        default: 4000,
        min: 0,
        max: MAX_PARTICLES as u32,
    },
    BuiltinParam {
        key: "size",
        meaning: "nominal particle diameter in centimetres (default 120, at most 10000)",
        default: 120,
        min: 1,
        max: 10_000,
    },
    BuiltinParam {
        key: "seed",
        meaning: "PCG32 seed for particle placement (default 1, any u32)",
        default: 1,
        min: 0,
        max: u32::MAX,
    },
    BuiltinParam {
        key: "extent",
        meaning: "the effect's scale in percent, positions and sizes (default 100, at most 1000)",
        default: 100,
        min: 1,
        max: 1000,
    },
];

pub(super) fn build(params: &Params, builder: &mut SceneBuilder) -> Result<(), SceneError> {
    let count = params.u32("count")?;
    let size = params.u32("size")?;
    let extent = params.u32("extent")?;
    let mut rng = Pcg32::new(u64::from(params.u32("seed")?));
    super::dense::build(params, builder)?;
    builder.ambient = [0.25; 3];
    let extent = extent as f32 / 100.0;
    let size = size as f32 / 100.0 * extent;
    let fire = count / 8;
    let smoke = (0..count - fire)
        .map(|_| {
            let y = rng.range(0.0, 4.0);
            let grey = rng.range(0.35, 0.75);
            Particle {
                position: in_disc(&mut rng, 2.0 + 1.25 * y, y) * f64::from(extent),
                size: size * rng.range(0.5, 1.5),
                color: [grey, grey, grey * 0.95],
                alpha: rng.range(0.05, 0.25),
                emissive: false,
            }
        })
        .collect();
    let fire = (0..fire)
        .map(|_| {
            let y = rng.range(0.0, 1.0);
            let radiance = rng.range(2.0, 6.0);
            Particle {
                position: in_disc(&mut rng, 1.2, y) * f64::from(extent),
                size: size * rng.range(0.3, 0.8),
                color: [radiance, radiance * 0.45, radiance * 0.1],
                alpha: rng.range(0.2, 0.6),
                emissive: true,
            }
        })
        .collect();
    builder.emitters = vec![
        ParticleEmitter {
            name: "smoke".to_owned(),
            particles: smoke,
        },
        ParticleEmitter {
            name: "fire".to_owned(),
            particles: fire,
        },
    ];
    Ok(())
}

/// A point uniform over the horizontal disc of `radius` around the y axis at height `y`.
fn in_disc(rng: &mut Pcg32, radius: f32, y: f32) -> DVec3 {
    let (r, angle) = (radius * rng.unit().sqrt(), rng.range(0.0, TAU));
    DVec3::new(
        f64::from(r * angle.cos()),
        f64::from(y),
        f64::from(r * angle.sin()),
    )
}
