//! Built-in procedural scenes, selected with `builtin:NAME[?key=value&...]`.
//!
//! Every scene is generated without I/O and is bit-identical for the same spec: fixed
//! constants plus, where randomness helps, a seeded [`rng::Pcg32`]. Each scene's module
//! documents what it contains and why it exists.

mod budget;
mod city;
mod dense;
mod lights;
mod params;
mod parts;
mod rng;
mod rocks;
mod shapes;
mod smoke;
mod solid;
mod spheres;
mod stage;
mod terrain;
mod unlit;

pub use params::BuiltinParam;
use params::Params;

use super::builder::SceneBuilder;
use super::{Scene, SceneError};

/// What [`super::Scene::load`] strips to find a built-in scene name.
pub const BUILTIN_PREFIX: &str = "builtin:";

/// A built-in scene: its name, a one-line description and the parameters it takes.
pub struct BuiltinScene {
    /// What follows `builtin:` in a scene spec.
    pub name: &'static str,
    /// One line, for `rgraph` help and the scene catalogue.
    pub description: &'static str,
    /// Each `?key=value` parameter accepted, with its default and largest value.
    pub params: &'static [BuiltinParam],
    build: fn(&Params, &mut SceneBuilder) -> Result<(), SceneError>,
}

const BUILTINS: &[BuiltinScene] = &[
    BuiltinScene {
        name: "spheres",
        description: "few edges: five large smooth spheres on a ground plane, 1 directional + 4 point lights; layers=1 adds a clear coat, a sheen and a tinted specular",
        params: spheres::PARAMS,
        build: spheres::build,
    },
    BuiltinScene {
        name: "dense",
        description: "many edges: grass blades, a wire fence, thin poles and interpenetrating boxes and spheres; 4 point + 2 spot lights",
        params: &[],
        build: dense::build,
    },
    BuiltinScene {
        name: "lights",
        description: "many lights: 256 point + 64 spot lights (seeded) over a floor with a grid of boxes and spheres",
        params: lights::PARAMS,
        build: lights::build,
    },
    BuiltinScene {
        name: "unlit",
        description: "analytic: four flat-colored UNLIT shapes at documented positions under an orthographic camera",
        params: &[],
        build: unlit::build,
    },
    BuiltinScene {
        name: "smoke",
        description: "particles: 3,500 blended smoke and 500 emissive fire particles (seeded) over the dense scene, filling most of the frame",
        params: smoke::PARAMS,
        build: smoke::build,
    },
    BuiltinScene {
        name: "terrain",
        description: "many triangles: one smooth, seeded heightfield of cells x cells (2 triangles each, 100,352 by default, up to 107 million); 1 directional + 4 point lights",
        params: terrain::PARAMS,
        build: terrain::build,
    },
    BuiltinScene {
        name: "city",
        description: "many meshes: blocks x blocks seeded box buildings (1,024 by default, up to 2.5 million), each its own mesh, on a ground plane; 1 directional + 4 point lights",
        params: city::PARAMS,
        build: city::build,
    },
    BuiltinScene {
        name: "rocks",
        description: "instanced: copies x one rock (3,968 triangles by default, detail up to 2048), every copy its own mesh sharing the rock's geometry (25 by default: 99,200 triangles; up to 1,048,575; 178,956,970 triangles in all at most), scattered on a ground plane; 1 directional + 4 point lights",
        params: rocks::PARAMS,
        build: rocks::build,
    },
];

/// All built-in scenes, in a stable order.
pub fn builtin_names() -> &'static [BuiltinScene] {
    BUILTINS
}

/// Builds `NAME[?params]` (the spec after `builtin:`).
pub(crate) fn build(spec: &str) -> Result<Scene, SceneError> {
    let (name, query) = spec.split_once('?').unwrap_or((spec, ""));
    let builtin =
        BUILTINS
            .iter()
            .find(|b| b.name == name)
            .ok_or_else(|| SceneError::UnknownBuiltin {
                name: name.to_owned(),
                available: BUILTINS
                    .iter()
                    .map(|b| b.name)
                    .collect::<Vec<_>>()
                    .join(", "),
            })?;
    let params = Params::parse(name, query, builtin.params)?;
    let mut builder = SceneBuilder::new(format!("{BUILTIN_PREFIX}{spec}"));
    (builtin.build)(&params, &mut builder)?;
    builder.finish()
}
