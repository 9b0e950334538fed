//! `builtin:spheres`: few geometric edges, the easy case for edge detection.
//!
//! - A 40 x 40 ground plane at y = 0 (grey, rough), 2 triangles.
//! - Five smooth spheres (48 x 24 tessellation, 2208 triangles each) resting on the ground and
//!   touching nothing else, so the only edges are silhouettes against the ground and sky:
//!   radius 1.5 at (0, 1.5, 0) red dielectric, 1.0 at (-3.5, 1, 1) gold metal, 1.2 at
//!   (3.2, 1.2, -0.5) glossy blue, 0.8 at (-1.5, 0.8, 3.2) rough green, 0.7 at (1.8, 0.7, 3)
//!   half-metallic white.
//! - Lights: one directional "sun" (2 lux, from above front-left) and four point lights
//!   (15 cd, range 10) at (±4, 2.5, ±4).
//! - Camera: perspective, 45° vertical FOV, eye (0, 4.5, 11) looking at (0, 1, 0), near 0.1,
//!   infinite far. Ambient 0.03.
//! - `layers=1`: three spheres wear glTF's material layers (scene/src/material_layers.rs),
//!   one each, so that a pipeline's cost of shading them can be measured beside the core
//!   model's (`rgraph bench --scene builtin:spheres?layers=0 --scene
//!   builtin:spheres?layers=1`): the red sphere a clear coat (roughness 0.05), the green a
//!   white sheen (roughness 0.5), the blue a warm specular colour at index of refraction 1.8.

use glam::{DVec3, Vec3};

use super::params::{BuiltinParam, Params};
use super::parts::{add_ground, corner_lights, directional, perspective_camera};
use super::shapes::Shape;
use super::solid::Solid;
use crate::builder::SceneBuilder;
use crate::material_layers::{Clearcoat, Sheen, Specular};
use crate::SceneError;

/// The parameters `builtin:spheres?...` takes.
pub(super) const PARAMS: &[BuiltinParam] = &[BuiltinParam {
    key: "layers",
    meaning: "1 gives the red, green and blue spheres a clear coat, a sheen and a tinted \
              specular (default 0: the core metallic-roughness model; at most 1)",
    default: 0,
    min: 0,
    max: 1,
}];

const SPHERES: [Solid; 5] = [
    Solid::sphere(
        "red sphere",
        [0.0, 1.5, 0.0],
        1.5,
        [0.8, 0.15, 0.1],
        0.0,
        0.4,
    ),
    Solid::sphere(
        "gold sphere",
        [-3.5, 1.0, 1.0],
        1.0,
        [1.0, 0.78, 0.34],
        1.0,
        0.3,
    ),
    Solid::sphere(
        "blue sphere",
        [3.2, 1.2, -0.5],
        1.2,
        [0.1, 0.3, 0.8],
        0.0,
        0.2,
    ),
    Solid::sphere(
        "green sphere",
        [-1.5, 0.8, 3.2],
        0.8,
        [0.2, 0.7, 0.25],
        0.0,
        0.7,
    ),
    Solid::sphere(
        "white sphere",
        [1.8, 0.7, 3.0],
        0.7,
        [0.9, 0.9, 0.9],
        0.5,
        0.5,
    ),
];

pub(super) fn build(params: &Params, builder: &mut SceneBuilder) -> Result<(), SceneError> {
    let layered = params.u32("layers")? == 1;
    add_ground(builder, "ground", 40.0, [0.5, 0.5, 0.5], 0.9);
    let sphere = Shape::uv_sphere(48, 24);
    for solid in &SPHERES {
        let material = solid.add_to(builder, &sphere);
        if layered {
            wear_layers(&mut builder.materials[material]);
        }
    }
    builder.lights.push(directional(
        "sun",
        Vec3::new(-0.4, -1.0, -0.3),
        [1.0, 0.96, 0.9],
        2.0,
    ));
    let colors = [
        [1.0, 0.8, 0.6],
        [0.6, 0.8, 1.0],
        [1.0, 0.6, 0.8],
        [0.7, 1.0, 0.7],
    ];
    builder
        .lights
        .extend(corner_lights(4.0, 2.5, colors, 15.0, 10.0));
    builder.ambient = [0.03; 3];
    builder.camera = Some(perspective_camera(
        "spheres",
        DVec3::new(0.0, 4.5, 11.0),
        DVec3::new(0.0, 1.0, 0.0),
        45.0,
    ));
    Ok(())
}

/// `layers=1`'s layers, by the sphere's material name; the others keep the core model.
fn wear_layers(material: &mut crate::Material) {
    match material.name.as_str() {
        "red sphere" => {
            material.clearcoat = Clearcoat {
                factor: 1.0,
                roughness_factor: 0.05,
                ..Clearcoat::default()
            }
        }
        "green sphere" => {
            material.sheen = Sheen {
                color_factor: [1.0; 3],
                roughness_factor: 0.5,
                ..Sheen::default()
            }
        }
        "blue sphere" => {
            material.ior = 1.8;
            material.specular = Specular {
                color_factor: [1.0, 0.8, 0.5],
                ..Specular::default()
            };
        }
        _ => {}
    }
}
