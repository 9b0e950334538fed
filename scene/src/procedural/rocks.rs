//! `builtin:rocks`: copies of one rock, every copy its own mesh sharing the rock's vertices
//! and indices, for measuring instanced geometry (issue 38: 100M instanced triangles), as
//! glTF's EXT_mesh_gpu_instancing places copies: the scene holds the rock once, the GPU
//! its vertices once and an index range per copy (passes' gpu_scene/shared_geometry.rs).
//!
//! - A 110 x 110 ground plane at y = 0 (mesh "ground").
//! - One rock: a unit UV sphere of `detail` segments and `detail / 2` rings (2 · detail ·
//!   (detail / 2 - 1) triangles: 3,968 at the default 64, 199,808 at 448; `copies=25202`
//!   of the default rock make 100,001,536).
//! - `copies` copies (default 25: 99,200 triangles, about the default terrain's) scattered
//!   over x, z in [-50, 50], each an ellipsoid:
//!   a base radius from the ground each copy has (0.35 √(10,000 / copies), at most 3),
//!   scaled 0.6 to 1.3 per axis, turned about +Y and tilted up to 20°, sunk to 40% of its
//!   height. Three stone materials, one per copy at random. Every draw comes from [`Pcg32`]
//!   seeded with `seed` (default 1), nine per copy in order, so each (copies, detail, seed)
//!   is one fixed scene.
//! - Lights and camera: the scale scenes' [`stage`], a sun and four point lights, the whole
//!   field in a 16:9 frame.
//! - Limits, checked before anything is built: `copies` at most 1,048,575 (with the ground,
//!   [`MAX_MESHES`](crate::MAX_MESHES)), `detail` 4 to 2,048, and copies times the rock's
//!   triangles at most 178,956,970: each copy's indices, 12 bytes a triangle, in the 2 GiB
//!   storage binding the compute raster reads them through.

use glam::{DMat4, DQuat, DVec3};

use super::budget::Geometry;
use super::params::{BuiltinParam, Params};
use super::parts::{add_ground, lit};
use super::rng::Pcg32;
use super::shapes::Shape;
use super::stage::{self, EXTENT};
use crate::builder::SceneBuilder;
use crate::{Mesh, SceneError, MAX_MESHES};

/// The most copies: the ground and the copies within the mesh limit.
const MAX_COPIES: u32 = MAX_MESHES - 1;
/// The finest rock: 4,190,208 triangles.
const MAX_DETAIL: u32 = 2048;
/// The most triangles of all copies: their indices, 12 bytes a triangle a copy on the
/// GPU, within a 2 GiB binding.
const MAX_TRIANGLES: u64 = (1 << 31) / 12;

/// The parameters `builtin:rocks?...` takes.
pub(super) const PARAMS: &[BuiltinParam] = &[
    BuiltinParam {
        key: "copies",
        meaning: "copies of the rock, each its own mesh sharing its geometry (default 25; \
                  at most 1048575: with the ground, the scene limit of 1,048,576 meshes)",
        default: 25,
        min: 1,
        max: MAX_COPIES,
    },
    BuiltinParam {
        key: "detail",
        meaning: "segments around the rock, half as many rings: 2 detail (detail / 2 - 1) \
                  triangles (default 64: 3,968; at most 2048; copies times triangles at most \
                  178,956,970)",
        default: 64,
        min: 4,
        max: MAX_DETAIL,
    },
    BuiltinParam {
        key: "seed",
        meaning: "PCG32 seed for the placements (default 1, any u32)",
        default: 1,
        min: 0,
        max: u32::MAX,
    },
];

/// The rock's triangles at `detail`.
const fn rock_triangles(detail: u64) -> u64 {
    2 * detail * (detail / 2 - 1)
}

/// The rock once (its vertices and indices) and a mesh record per copy and the ground: what
/// the scene holds, shared geometry counted once.
const fn geometry(copies: u64, detail: u64) -> Geometry {
    let rock = Geometry {
        vertices: (detail + 1) * (detail / 2 + 1),
        indices: 3 * rock_triangles(detail),
        meshes: 0,
    };
    let ground = Geometry {
        vertices: 4,
        indices: 6,
        meshes: 1,
    };
    rock.plus(ground).plus(Geometry {
        vertices: 0,
        indices: 0,
        meshes: copies,
    })
}

pub(super) fn build(params: &Params, builder: &mut SceneBuilder) -> Result<(), SceneError> {
    let (copies, detail) = (params.u32("copies")?, params.u32("detail")?);
    let error = |reason: String| SceneError::BuiltinParameter {
        scene: "rocks".to_owned(),
        reason,
    };
    let triangles = u64::from(copies) * rock_triangles(u64::from(detail));
    if triangles > MAX_TRIANGLES {
        return Err(error(format!(
            "`copies={copies}&detail={detail}`: {triangles} triangles in all, more than \
             {MAX_TRIANGLES} (each copy's indices, 12 bytes a triangle on the GPU, within a \
             2 GiB binding)"
        )));
    }
    debug_assert!(geometry(u64::from(copies), u64::from(detail)).fits());
    let mut rng = Pcg32::new(u64::from(params.u32("seed")?));
    add_ground(builder, "ground", 110.0, [0.35, 0.33, 0.3], 0.95);
    let materials = [
        lit("granite", [0.45, 0.44, 0.42], 0.0, 0.8),
        lit("sandstone", [0.62, 0.5, 0.36], 0.0, 0.9),
        lit("basalt", [0.2, 0.2, 0.21], 0.0, 0.7),
    ]
    .map(|m| builder.add_material(m));
    let rock = Shape::uv_sphere(detail, detail / 2);
    let (vertices, indices) = (rock.vertices.into(), rock.indices.into());
    let radius = (0.35 * (4.0 * EXTENT * EXTENT / f64::from(copies)).sqrt()).min(3.0);
    builder.meshes.reserve_exact(copies as usize);
    for copy in 0..copies {
        let mut draw = |low: f32, high: f32| f64::from(rng.range(low, high));
        let (x, z) = (
            draw(-EXTENT as f32, EXTENT as f32),
            draw(-EXTENT as f32, EXTENT as f32),
        );
        let scale = DVec3::new(draw(0.6, 1.3), draw(0.6, 1.3), draw(0.6, 1.3)) * radius;
        let turn = draw(0.0, std::f32::consts::TAU);
        let tilt = DVec3::new(draw(-1.0, 1.0), 0.0, draw(-1.0, 1.0));
        let lean = draw(0.0, 20.0).to_radians();
        let material = materials[(rng.next_u32() % 3) as usize];
        let rotation = DQuat::from_axis_angle(tilt.try_normalize().unwrap_or(DVec3::X), lean)
            * DQuat::from_rotation_y(turn);
        let transform = DMat4::from_scale_rotation_translation(
            scale,
            rotation,
            DVec3::new(x, 0.4 * scale.y, z),
        );
        builder.meshes.push(Mesh {
            name: format!("rock {copy}"),
            vertices: std::sync::Arc::clone(&vertices),
            indices: std::sync::Arc::clone(&indices),
            material,
            transform,
        });
    }
    stage::light_and_frame(builder, "rocks");
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_limits_are_the_documented_ones() {
        assert_eq!(MAX_TRIANGLES, 178_956_970);
        assert_eq!(rock_triangles(64), 3968);
        assert_eq!(rock_triangles(448), 199_808);
        assert!(25_202 * rock_triangles(64) > 100_000_000);
        assert_eq!(rock_triangles(2048), 4_190_208);
        // The largest field within every limit holds its geometry once.
        assert!(geometry(u64::from(MAX_COPIES), u64::from(MAX_DETAIL)).fits());
        assert!(PARAMS[0].meaning.contains("at most 1048575"));
        assert!(PARAMS[1].meaning.contains("at most 2048"));
    }

    #[test]
    fn counts_match_the_shapes_built() {
        let rock = Shape::uv_sphere(64, 32);
        let counted = geometry(0, 64);
        assert_eq!(rock.vertices.len() as u64 + 4, counted.vertices);
        assert_eq!(rock.indices.len() as u64 + 6, counted.indices);
        assert_eq!(rock.indices.len() as u64, 3 * rock_triangles(64));
    }
}
