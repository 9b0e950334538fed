//! `builtin:dense`: as many geometric edges as possible, the hard case for edge detection.
//!
//! - A 30 x 30 ground plane at y = 0.
//! - Grass: 160 x 160 blades (3 triangles each, 76 800 in all) jittered over x, z in
//!   [-12, 12], 0.25–0.6 tall and 2.5–5 cm wide, random yaw and lean, merged into one
//!   double-sided mesh: thousands of sub-pixel-wide silhouettes.
//! - A wire fence along z = -6 from x = -10 to 10: 11 posts (4 cm radius, 1.2 tall) and four
//!   8 mm wires at heights 0.3, 0.6, 0.9 and 1.15: long edges thinner than a pixel.
//! - Nine thin poles (2.5 cm radius, 3 tall) along x = 7, z = -4..4.
//! - Interpenetrating solids, whose intersection edges have no depth discontinuity and full
//!   coverage by both surfaces: a box standing in a plinth with a sphere sunk into its corner,
//!   two crossed boxes forming a plus, and a sphere sunk into the ground and pierced by a slab.
//! - Lights: four point lights (8 cd, range 8) at (±2.5, 1.8, ±2.5) and two spot lights
//!   (80 cd, range 16, cones 0.25/0.45 rad) aimed at the solids; no directional light.
//! - Camera: perspective, 50° vertical FOV, eye (0, 3.2, 9) looking at (0, 0.7, 0). Ambient 0.05.
//!
//! Randomness comes from [`Pcg32`] seeded with a constant, so the scene is fixed.

use std::f32::consts::{FRAC_PI_2, TAU};

use glam::{DMat4, DVec3, Mat4, Quat, Vec3};

use super::params::Params;
use super::parts::{add_ground, add_shape, corner_lights, lit, perspective_camera, spot};
use super::rng::Pcg32;
use super::shapes::Shape;
use super::solid::Solid;
use crate::builder::SceneBuilder;
use crate::SceneError;

const GRASS_PER_SIDE: u32 = 160;
const GRASS_EXTENT: f32 = 12.0;
const SEED: u64 = 0x00de_75e0;

pub(super) fn build(_: &Params, builder: &mut SceneBuilder) -> Result<(), SceneError> {
    add_ground(builder, "ground", 30.0, [0.35, 0.3, 0.25], 0.95);
    let grass = builder.add_material(crate::Material {
        double_sided: true,
        ..lit("grass", [0.25, 0.55, 0.12], 0.0, 0.8)
    });
    add_shape(
        builder,
        "grass",
        grass_field(&mut Pcg32::new(SEED)),
        grass,
        DMat4::IDENTITY,
    );
    let metal = builder.add_material(lit("galvanized metal", [0.6, 0.6, 0.62], 1.0, 0.45));
    add_shape(builder, "fence", fence(), metal, DMat4::IDENTITY);
    add_shape(builder, "poles", poles(), metal, DMat4::IDENTITY);
    let sphere = Shape::uv_sphere(48, 24);
    for solid in &SOLIDS {
        solid.add_to(builder, &sphere);
    }
    let colors = [
        [1.0, 0.7, 0.4],
        [0.5, 0.7, 1.0],
        [1.0, 0.5, 0.7],
        [0.6, 1.0, 0.6],
    ];
    builder
        .lights
        .extend(corner_lights(2.5, 1.8, colors, 8.0, 8.0));
    for (i, (from, to)) in [
        ([-4.0, 6.0, 4.0], [0.0, 0.5, 0.0]),
        ([4.0, 6.0, -2.0], [2.8, 0.5, 2.0]),
    ]
    .into_iter()
    .enumerate()
    {
        let (from, to) = (Vec3::from_array(from), Vec3::from_array(to));
        builder.lights.push(spot(
            format!("spot {i}"),
            from.as_dvec3(),
            to - from,
            (0.25, 0.45),
            [1.0, 0.95, 0.85],
            80.0,
            16.0,
        ));
    }
    builder.ambient = [0.05; 3];
    builder.camera = Some(perspective_camera(
        "dense",
        DVec3::new(0.0, 3.2, 9.0),
        DVec3::new(0.0, 0.7, 0.0),
        50.0,
    ));
    Ok(())
}

/// Jittered grid of blades, transforms baked in.
fn grass_field(rng: &mut Pcg32) -> Shape {
    let blade = Shape::blade();
    let cell = 2.0 * GRASS_EXTENT / GRASS_PER_SIDE as f32;
    let mut field = Shape::default();
    for row in 0..GRASS_PER_SIDE {
        for column in 0..GRASS_PER_SIDE {
            let x = -GRASS_EXTENT + (column as f32 + rng.unit()) * cell;
            let z = -GRASS_EXTENT + (row as f32 + rng.unit()) * cell;
            let rotation = Quat::from_rotation_y(rng.range(0.0, TAU))
                * Quat::from_rotation_x(rng.range(-0.3, 0.3));
            let size = Vec3::new(rng.range(0.025, 0.05), rng.range(0.25, 0.6), 1.0);
            field.append(&blade.transformed(Mat4::from_scale_rotation_translation(
                size,
                rotation,
                Vec3::new(x, 0.0, z),
            )));
        }
    }
    field
}

/// An open cylinder of `radius` from `base` along the rotated +Y axis for `length`.
fn rod(base: Vec3, rotation: Quat, radius: f32, length: f32) -> Shape {
    Shape::cylinder(8).transformed(Mat4::from_scale_rotation_translation(
        Vec3::new(radius, length, radius),
        rotation,
        base,
    ))
}

fn fence() -> Shape {
    let mut fence = Shape::default();
    for post in 0..11 {
        fence.append(&rod(
            Vec3::new(-10.0 + 2.0 * post as f32, 0.0, -6.0),
            Quat::IDENTITY,
            0.04,
            1.2,
        ));
    }
    // Rotating +Y onto +X lays a rod along the fence.
    let along_x = Quat::from_rotation_z(-FRAC_PI_2);
    for height in [0.3, 0.6, 0.9, 1.15] {
        fence.append(&rod(Vec3::new(-10.0, height, -6.0), along_x, 0.008, 20.0));
    }
    fence
}

fn poles() -> Shape {
    let mut poles = Shape::default();
    for i in 0..9 {
        poles.append(&rod(
            Vec3::new(7.0, 0.0, -4.0 + i as f32),
            Quat::IDENTITY,
            0.025,
            3.0,
        ));
    }
    poles
}

const SOLIDS: [Solid; 7] = [
    Solid::cuboid(
        "box",
        [0.0, 0.75, 0.0],
        [1.5; 3],
        30.0,
        [0.8, 0.5, 0.2],
        0.0,
        0.5,
    ),
    Solid::cuboid(
        "plinth",
        [0.0, 0.1, 0.0],
        [2.6, 0.2, 2.6],
        0.0,
        [0.5, 0.5, 0.55],
        0.0,
        0.5,
    ),
    Solid::sphere(
        "sphere in box",
        [0.8, 1.2, 0.5],
        0.8,
        [0.2, 0.4, 0.9],
        0.0,
        0.5,
    ),
    Solid::cuboid(
        "cross bar x",
        [-2.5, 0.6, 1.0],
        [2.0, 1.2, 0.6],
        45.0,
        [0.85, 0.85, 0.8],
        0.0,
        0.5,
    ),
    Solid::cuboid(
        "cross bar z",
        [-2.5, 0.6, 1.0],
        [0.6, 1.6, 2.0],
        10.0,
        [0.7, 0.2, 0.2],
        0.0,
        0.5,
    ),
    Solid::sphere(
        "sunken sphere",
        [2.8, 0.5, 2.0],
        0.9,
        [0.3, 0.75, 0.35],
        0.0,
        0.5,
    ),
    Solid::cuboid(
        "slab",
        [2.8, 0.9, 2.0],
        [0.4, 1.8, 2.4],
        20.0,
        [0.9, 0.85, 0.3],
        0.0,
        0.5,
    ),
];
