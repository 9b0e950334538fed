//! `builtin:terrain`: one smooth heightfield whose triangle count scales from 2 to over
//! 10^8 while the view stays the same, for measuring how cost grows with triangles (issue
//! 38): the raster's time with the triangle count, and the shading of a pixel whose samples
//! show several triangles of one continuous surface.
//!
//! - One mesh, "terrain": `cells` x `cells` square cells over x, z in [-50, 50], 2
//!   triangles each (2 · cells² in all: 100,352 at the default 224, 100,026,368 at 7072),
//!   on (cells + 1)² shared vertices with smooth normals (central differences of the
//!   heights; one-sided at the border), uv = (x, z) mapped to [0, 1].
//! - Heights from 0 to 12.9: value noise of five octaves (3, 7, 17, 41 and 97 lattice cells
//!   across, amplitudes 8, 3, 1.2, 0.5 and 0.2, quintic fade), the lattices drawn from
//!   [`Pcg32`] seeded with `seed` (default 1). Each (cells, seed) is one fixed scene, and one
//!   seed is one landscape at every `cells`, sampled finer or coarser.
//! - Vertex colors: grass, turning to rock from height 4 to 7 and on slopes from 32° to
//!   41°, and to snow from 9 to 10.5; one white, rough material.
//! - Lights and camera: the scale scenes' [`stage`], a sun and four point lights, the
//!   whole terrain in a 16:9 frame.
//! - `cells` is at most 7326 (107,340,552 triangles): the most whose vertices, indices and
//!   mesh, counted from the parameter before anything is built, fit the 4 GiB scene limit
//!   ([`budget`](super::budget)).

use glam::{DMat4, Vec3};

use super::budget::Geometry;
use super::params::{BuiltinParam, Params};
use super::parts::lit;
use super::rng::Pcg32;
use super::stage::{self, EXTENT};
use crate::builder::SceneBuilder;
use crate::{Mesh, SceneError, Vertex};

/// Value-noise octaves: lattice cells across the terrain and amplitude.
const OCTAVES: [(u32, f32); 5] = [(3, 8.0), (7, 3.0), (17, 1.2), (41, 0.5), (97, 0.2)];

/// The vertices and indices of a terrain of `cells` x `cells`.
const fn geometry(cells: u64) -> Geometry {
    Geometry {
        vertices: (cells + 1) * (cells + 1),
        indices: 6 * cells * cells,
        meshes: 1,
    }
}

/// The most cells per side whose geometry fits the scene limit.
const MAX_CELLS: u32 = {
    let mut cells = 0;
    while geometry(cells as u64 + 1).fits() {
        cells += 1;
    }
    cells
};

/// The parameters `builtin:terrain?...` takes.
pub(super) const PARAMS: &[BuiltinParam] = &[
    BuiltinParam {
        key: "cells",
        meaning: "cells per side of the heightfield, 2 triangles each (default 224: 100,352 \
                  triangles; at most 7326: 107,340,552 triangles in 4,294,442,824 \
                  bytes of vertices, indices and mesh, the most that fit the 4 GiB scene \
                  limit)",
        default: 224,
        min: 1,
        max: MAX_CELLS,
    },
    BuiltinParam {
        key: "seed",
        meaning: "PCG32 seed for the heights (default 1, any u32)",
        default: 1,
        min: 0,
        max: u32::MAX,
    },
];

pub(super) fn build(params: &Params, builder: &mut SceneBuilder) -> Result<(), SceneError> {
    let cells = params.u32("cells")?;
    let octaves = Octave::draw(&mut Pcg32::new(u64::from(params.u32("seed")?)));
    let material = builder.add_material(lit("terrain", [1.0; 3], 0.0, 0.9));
    builder.meshes.push(Mesh {
        name: "terrain".to_owned(),
        vertices: vertices(cells, &octaves).into(),
        indices: indices(cells).into(),
        material,
        transform: DMat4::IDENTITY,
    });
    stage::light_and_frame(builder, "terrain");
    Ok(())
}

/// One octave of value noise: random values at the corners of a square lattice over the
/// terrain, blended with a quintic fade between them (so heights and their slopes are
/// continuous across lattice cells).
struct Octave {
    cells: u32,
    amplitude: f32,
    /// (cells + 1)² values in [0, 1), row by row.
    lattice: Vec<f32>,
}

impl Octave {
    /// The five octaves of [`OCTAVES`], their lattices drawn from `rng` in order.
    fn draw(rng: &mut Pcg32) -> Vec<Octave> {
        OCTAVES
            .iter()
            .map(|&(cells, amplitude)| Octave {
                cells,
                amplitude,
                lattice: (0..(cells + 1) * (cells + 1)).map(|_| rng.unit()).collect(),
            })
            .collect()
    }

    /// Where `t` in [0, 1] falls along one axis: the lattice cell and the faded weight of
    /// its far side.
    fn along(&self, t: f32) -> (usize, f32) {
        let x = t * self.cells as f32;
        let cell = (x as u32).min(self.cells - 1);
        let f = x - cell as f32;
        (cell as usize, f * f * f * (f * (f * 6.0 - 15.0) + 10.0))
    }

    /// The octave's height at lattice position `(column, row)` from [`Octave::along`].
    fn at(&self, (x, fx): (usize, f32), (z, fz): (usize, f32)) -> f32 {
        let row = self.cells as usize + 1;
        let value = |x: usize, z: usize| self.lattice[z * row + x];
        let near = value(x, z) + (value(x + 1, z) - value(x, z)) * fx;
        let far = value(x, z + 1) + (value(x + 1, z + 1) - value(x, z + 1)) * fx;
        self.amplitude * (near + (far - near) * fz)
    }
}

/// The (cells + 1)² vertices, row by row (z), each row along x: positions, then normals
/// and colors from the neighbours' heights.
fn vertices(cells: u32, octaves: &[Octave]) -> Vec<Vertex> {
    let side = cells as usize + 1;
    let count = geometry(u64::from(cells)).vertices as usize;
    let coordinate = |k: usize| k as f32 / cells as f32;
    let extent = EXTENT as f32;
    // Each column's place in every octave, computed once rather than once per row.
    let columns: Vec<Vec<(usize, f32)>> = (0..side)
        .map(|i| octaves.iter().map(|o| o.along(coordinate(i))).collect())
        .collect();
    let mut vertices = Vec::with_capacity(count);
    for j in 0..side {
        let v = coordinate(j);
        let rows: Vec<(usize, f32)> = octaves.iter().map(|o| o.along(v)).collect();
        for (i, column) in columns.iter().enumerate() {
            let u = coordinate(i);
            let height = octaves
                .iter()
                .zip(column.iter().zip(&rows))
                .map(|(octave, (&x, &z))| octave.at(x, z))
                .sum();
            vertices.push(Vertex {
                position: [extent * (2.0 * u - 1.0), height, extent * (2.0 * v - 1.0)],
                normal: [0.0, 1.0, 0.0],
                uv: [u, v],
                color: Vertex::WHITE,
                tangent: Vertex::NO_TANGENT,
                uv1: [0.0; 2],
            });
        }
    }
    // Slopes by central differences, one-sided at the border.
    let spacing = 2.0 * extent / cells as f32;
    let height = |vertices: &[Vertex], i: usize, j: usize| vertices[j * side + i].position[1];
    for j in 0..side {
        let (below, above) = (j.saturating_sub(1), (j + 1).min(side - 1));
        for i in 0..side {
            let (left, right) = (i.saturating_sub(1), (i + 1).min(side - 1));
            let dx = (height(&vertices, right, j) - height(&vertices, left, j))
                / (spacing * (right - left) as f32);
            let dz = (height(&vertices, i, above) - height(&vertices, i, below))
                / (spacing * (above - below) as f32);
            let normal = Vec3::new(-dx, 1.0, -dz).normalize();
            let vertex = &mut vertices[j * side + i];
            vertex.normal = normal.to_array();
            vertex.color = Vertex::color_from(color(vertex.position[1], normal.y));
        }
    }
    vertices
}

/// Grass, rock by height or slope (`up` is the normal's y), snow by height.
fn color(height: f32, up: f32) -> [f32; 4] {
    const GRASS: Vec3 = Vec3::new(0.16, 0.32, 0.08);
    const ROCK: Vec3 = Vec3::new(0.33, 0.28, 0.23);
    const SNOW: Vec3 = Vec3::new(0.9, 0.9, 0.93);
    let rock = smoothstep(4.0, 7.0, height).max(smoothstep(0.85, 0.75, up));
    let snow = smoothstep(9.0, 10.5, height);
    GRASS
        .lerp(ROCK, rock)
        .lerp(SNOW, snow)
        .extend(1.0)
        .to_array()
}

/// 0 at `from`, 1 at `to` (either order), smooth between.
fn smoothstep(from: f32, to: f32, x: f32) -> f32 {
    let t = ((x - from) / (to - from)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// Two counter-clockwise (seen from above) triangles per cell, row by row.
fn indices(cells: u32) -> Vec<u32> {
    let side = cells + 1;
    let mut indices = Vec::with_capacity(geometry(u64::from(cells)).indices as usize);
    for j in 0..cells {
        for i in 0..cells {
            let a = j * side + i;
            let (b, d) = (a + 1, a + side);
            indices.extend([a, d, b, b, d, d + 1]);
        }
    }
    indices
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_largest_terrain_is_over_1e8_triangles_within_the_scene_limit() {
        let triangles = |cells: u64| geometry(cells).indices / 3;
        assert_eq!(MAX_CELLS, 7326);
        assert_eq!(triangles(7326), 107_340_552);
        assert_eq!(geometry(7326).bytes(), 4_294_442_824);
        assert!(!geometry(7327).fits());
        assert!(triangles(7072) > 100_000_000);
        assert!(PARAMS[0]
            .meaning
            .contains("at most 7326: 107,340,552 triangles in 4,294,442,824 bytes"));
    }

    #[test]
    fn counts_match_what_is_built() {
        let octaves = Octave::draw(&mut Pcg32::new(1));
        for cells in [1, 2, 5] {
            let (vertices, indices) = (vertices(cells, &octaves), indices(cells));
            let counted = geometry(u64::from(cells));
            assert_eq!(vertices.len() as u64, counted.vertices);
            assert_eq!(indices.len() as u64, counted.indices);
            assert_eq!(
                (vertices.capacity(), indices.capacity()),
                (vertices.len(), indices.len())
            );
            assert!(indices.iter().all(|&i| (i as usize) < vertices.len()));
        }
    }

    #[test]
    fn heights_stay_within_the_sum_of_the_amplitudes() {
        let octaves = Octave::draw(&mut Pcg32::new(7));
        let most: f32 = OCTAVES.iter().map(|o| o.1).sum();
        for vertex in vertices(64, &octaves) {
            let y = vertex.position[1];
            assert!((0.0..most).contains(&y), "{y}");
            assert!(vertex.normal[1] > 0.0);
        }
    }
}
