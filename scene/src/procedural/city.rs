//! `builtin:city`: a grid of buildings, each its own mesh, for measuring how cost grows with
//! the number of meshes (issue 38): a renderer's per-mesh work on the CPU (one draw, one
//! record of per-mesh data each) against a few triangles per mesh.
//!
//! - A 110 x 110 asphalt ground plane at y = 0 (mesh "ground").
//! - `blocks` x `blocks` buildings over x, z in [-50, 50] (default 32: 1,024 buildings), one
//!   per block of side 100 / `blocks`, each a box (12 triangles) and its own mesh named
//!   `building ROW,COLUMN`: the unit cube placed by its transform. Footprints 0.5 to 0.8 of
//!   the block per side, centred in it; heights 0.6 to 2.4 times the block's side (the
//!   random draw squared, so most are low), times up to 4 towards the centre ("downtown",
//!   falling off to 1 at distance 70), at most 30. Four materials (concrete, sandstone,
//!   brick, blue-grey glass), one per building at random. Every draw comes from [`Pcg32`]
//!   seeded with `seed` (default 1), four per building in row order, so each (blocks, seed)
//!   is one fixed scene. The city covers the same ground at every size, its buildings
//!   shrinking with their blocks: past a few hundred blocks it is a carpet of sub-pixel
//!   boxes, as many meshes as asked for in the same view.
//! - Lights and camera: the scale scenes' [`stage`], a sun and four point lights, the whole
//!   city in a 16:9 frame.
//! - `blocks` is at most 1023 (1,046,529 buildings and the ground, 12,558,350 triangles): the most whose
//!   meshes, counted from the parameter before anything is built, fit the scene limit of
//!   [`MAX_MESHES`](crate::MAX_MESHES) ([`budget`](super::budget)); their memory is well
//!   within the 4 GiB.

use glam::{DMat4, DVec3};

use super::budget::Geometry;
use super::params::{BuiltinParam, Params};
use super::parts::{add_ground, add_shape, lit};
use super::rng::Pcg32;
use super::shapes::Shape;
use super::stage::{self, EXTENT};
use crate::builder::SceneBuilder;
use crate::SceneError;

/// The tallest building.
const MAX_HEIGHT: f64 = 30.0;

/// One building: [`Shape::cuboid`], 4 vertices and 2 triangles per face, its own mesh.
const BUILDING: Geometry = Geometry {
    vertices: 24,
    indices: 36,
    meshes: 1,
};

/// The ground: [`Shape::plane`].
const GROUND: Geometry = Geometry {
    vertices: 4,
    indices: 6,
    meshes: 1,
};

/// The ground and `blocks` x `blocks` buildings.
const fn geometry(blocks: u64) -> Geometry {
    BUILDING.times(blocks * blocks).plus(GROUND)
}

/// The most blocks per side whose geometry fits the scene limit.
const MAX_BLOCKS: u32 = {
    let mut blocks = 0;
    while geometry(blocks as u64 + 1).fits() {
        blocks += 1;
    }
    blocks
};

/// The parameters `builtin:city?...` takes.
pub(super) const PARAMS: &[BuiltinParam] = &[
    BuiltinParam {
        key: "blocks",
        meaning: "blocks per side, one building each, each building its own mesh (default \
                  32: 1,024 buildings; at most 1023: 1,046,529 buildings and the \
                  ground, the most within the scene limit of 1,048,576 meshes)",
        default: 32,
        min: 1,
        max: MAX_BLOCKS,
    },
    BuiltinParam {
        key: "seed",
        meaning: "PCG32 seed for the buildings (default 1, any u32)",
        default: 1,
        min: 0,
        max: u32::MAX,
    },
];

pub(super) fn build(params: &Params, builder: &mut SceneBuilder) -> Result<(), SceneError> {
    let blocks = params.u32("blocks")?;
    let mut rng = Pcg32::new(u64::from(params.u32("seed")?));
    add_ground(builder, "ground", 110.0, [0.2, 0.2, 0.22], 0.9);
    let materials = [
        lit("concrete", [0.55, 0.55, 0.53], 0.0, 0.8),
        lit("sandstone", [0.7, 0.58, 0.42], 0.0, 0.7),
        lit("brick", [0.48, 0.22, 0.16], 0.0, 0.85),
        lit("glass", [0.3, 0.38, 0.48], 0.6, 0.25),
    ]
    .map(|m| builder.add_material(m));
    // One allocation for the buildings' records, as counted.
    builder
        .meshes
        .reserve_exact(blocks as usize * blocks as usize);
    let cube = Shape::cuboid();
    let block = 2.0 * EXTENT / f64::from(blocks);
    for row in 0..blocks {
        for column in 0..blocks {
            let center = |k: u32| -EXTENT + (f64::from(k) + 0.5) * block;
            let (x, z) = (center(column), center(row));
            let width = block * f64::from(rng.range(0.5, 0.8));
            let depth = block * f64::from(rng.range(0.5, 0.8));
            let tall = f64::from(rng.unit());
            // sqrt, not hypot: IEEE rounds it exactly, the platform's libm need not.
            let downtown = (1.0 - (x * x + z * z).sqrt() / 70.0).max(0.0);
            let height = (block * (0.6 + 1.8 * tall * tall) * (1.0 + 3.0 * downtown * downtown))
                .min(MAX_HEIGHT);
            let material = materials[(rng.next_u32() % 4) as usize];
            let transform = DMat4::from_translation(DVec3::new(x, 0.5 * height, z))
                * DMat4::from_scale(DVec3::new(width, height, depth));
            let name = format!("building {row},{column}");
            add_shape(builder, &name, cube.clone(), material, transform);
        }
    }
    stage::light_and_frame(builder, "city");
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_largest_city_fits_the_scene_limit() {
        assert_eq!(MAX_BLOCKS, 1023);
        let most = geometry(1023);
        assert_eq!(most.meshes, 1_046_530);
        assert_eq!(most.indices / 3, 12_558_350);
        assert!(most.bytes() < crate::DEFAULT_MAX_SCENE_BYTES);
        assert!(!geometry(1024).fits(), "1,048,577 meshes");
        assert!(PARAMS[0]
            .meaning
            .contains("at most 1023: 1,046,529 buildings and the ground"));
    }

    #[test]
    fn counts_match_the_shapes_built() {
        for (shape, counted) in [(Shape::cuboid(), BUILDING), (Shape::plane(), GROUND)] {
            assert_eq!(shape.vertices.len() as u64, counted.vertices);
            assert_eq!(shape.indices.len() as u64, counted.indices);
        }
    }
}
