//! `builtin:lights`: hundreds of local lights, the case deferred shading exists for.
//!
//! - A 40 x 40 floor at y = 0 and a 6 x 6 grid of solids (spacing 6, x and z in -15..15),
//!   alternating 1.5 x 2.5 x 1.5 boxes and radius-1 spheres standing on the floor.
//! - `count` lights (default 320, at most [`MAX_LIGHTS`]): `count - count / 5` point lights (256 by default) and
//!   `count / 5` spot lights (64), no directional light. Placement comes from [`Pcg32`] seeded
//!   with `seed` (default 1), so each (count, seed) gives one fixed scene:
//!   - point lights at x, z in [-20, 20), y in [0.3, 3), 2–6 cd, range 4–7;
//!   - spot lights at x, z in [-18, 18), y in [4, 7), aimed down with up to 25° tilt, outer
//!     cone 0.3–0.7 rad, inner cone 0.6 × outer, 20–60 cd, range 10–14;
//!   - saturated random hues (HSV saturation 0.7, value 1).
//! - Camera: perspective, 50° vertical FOV, eye (0, 14, 30) looking at the origin.
//!   Ambient 0.01.

use std::f32::consts::TAU;

use glam::{DMat4, DVec3, Vec3};

use super::params::{BuiltinParam, Params};
use super::parts::{add_ground, add_shape, lit, perspective_camera, spot};
use super::rng::Pcg32;
use super::shapes::Shape;
use crate::builder::SceneBuilder;
use crate::{Light, SceneError, MAX_LIGHTS};

/// The parameters `builtin:lights?...` takes.
pub(super) const PARAMS: &[BuiltinParam] = &[
    BuiltinParam {
        key: "count",
        meaning: "total number of lights, 4/5 point and 1/5 spot (default 320, at most 65536)",
        default: 320,
        min: 0,
        max: MAX_LIGHTS,
    },
    BuiltinParam {
        key: "seed",
        meaning: "PCG32 seed for light placement (default 1, any u32)",
        default: 1,
        min: 0,
        max: u32::MAX,
    },
];

pub(super) fn build(params: &Params, builder: &mut SceneBuilder) -> Result<(), SceneError> {
    let count = params.u32("count")?;
    let mut rng = Pcg32::new(u64::from(params.u32("seed")?));
    add_ground(builder, "floor", 40.0, [0.6, 0.6, 0.6], 0.7);
    add_solids(builder);
    let spots = count / 5;
    for i in 0..count - spots {
        let position = DVec3::new(
            f64::from(rng.range(-20.0, 20.0)),
            f64::from(rng.range(0.3, 3.0)),
            f64::from(rng.range(-20.0, 20.0)),
        );
        let color = hue(&mut rng);
        builder.lights.push(Light::point(
            format!("point {i}"),
            position,
            color,
            rng.range(2.0, 6.0),
            Some(rng.range(4.0, 7.0)),
        ));
    }
    for i in 0..spots {
        let position = DVec3::new(
            f64::from(rng.range(-18.0, 18.0)),
            f64::from(rng.range(4.0, 7.0)),
            f64::from(rng.range(-18.0, 18.0)),
        );
        let (tilt, azimuth) = (rng.range(0.0, 25f32.to_radians()), rng.range(0.0, TAU));
        let direction = Vec3::new(
            tilt.sin() * azimuth.cos(),
            -tilt.cos(),
            tilt.sin() * azimuth.sin(),
        );
        let outer = rng.range(0.3, 0.7);
        let color = hue(&mut rng);
        builder.lights.push(spot(
            format!("spot {i}"),
            position,
            direction,
            (0.6 * outer, outer),
            color,
            rng.range(20.0, 60.0),
            rng.range(10.0, 14.0),
        ));
    }
    builder.ambient = [0.01; 3];
    builder.camera = Some(perspective_camera(
        "lights",
        DVec3::new(0.0, 14.0, 30.0),
        DVec3::ZERO,
        50.0,
    ));
    Ok(())
}

fn add_solids(builder: &mut SceneBuilder) {
    let (cube, sphere) = (Shape::cuboid(), Shape::uv_sphere(32, 16));
    let box_material = builder.add_material(lit("box", [0.8, 0.8, 0.75], 0.0, 0.5));
    let sphere_material = builder.add_material(lit("sphere", [0.75, 0.8, 0.8], 0.3, 0.35));
    for row in 0..6 {
        for column in 0..6 {
            let (x, z) = (
                -15.0 + 6.0 * f64::from(column),
                -15.0 + 6.0 * f64::from(row),
            );
            let name = format!("solid {row},{column}");
            if (row + column) % 2 == 0 {
                let transform = DMat4::from_translation(DVec3::new(x, 1.25, z))
                    * DMat4::from_scale(DVec3::new(1.5, 2.5, 1.5));
                add_shape(builder, &name, cube.clone(), box_material, transform);
            } else {
                add_shape(
                    builder,
                    &name,
                    sphere.clone(),
                    sphere_material,
                    DMat4::from_translation(DVec3::new(x, 1.0, z)),
                );
            }
        }
    }
}

/// A saturated color of random hue (HSV with s = 0.7, v = 1), linear RGB.
fn hue(rng: &mut Pcg32) -> [f32; 3] {
    let h = rng.range(0.0, 6.0);
    let channel = |offset: f32| {
        let k = (offset + h) % 6.0;
        1.0 - 0.7 * (k.min(4.0 - k)).clamp(0.0, 1.0)
    };
    [channel(5.0), channel(3.0), channel(1.0)]
}
