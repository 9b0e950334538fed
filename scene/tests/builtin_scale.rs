//! The scale scenes, `builtin:terrain` (triangles) and `builtin:city` (meshes): exact counts
//! at a few sizes, one scene per spec, and sizes past the 4 GiB scene limit refused, naming the parameter and the
//! limit, before anything is built.

use std::time::{Duration, Instant};

use rgraph_scene::{Scene, SceneError};

use crate::allocations::allocated_by;

fn builtin(spec: &str) -> Scene {
    Scene::load(spec).unwrap_or_else(|e| panic!("{e}"))
}

/// (directional, point, spot) lights.
fn lights(scene: &Scene) -> (usize, usize, usize) {
    let stats = scene.stats();
    (
        stats.directional_lights,
        stats.point_lights,
        stats.spot_lights,
    )
}

#[test]
fn terrain_has_two_triangles_per_cell_on_shared_vertices() {
    for (spec, cells) in [
        ("builtin:terrain?cells=1", 1),
        ("builtin:terrain?cells=7", 7),
        ("builtin:terrain?cells=100", 100),
        ("builtin:terrain", 224),
    ] {
        let scene = builtin(spec);
        let stats = scene.stats();
        assert_eq!(stats.meshes, 1, "{spec}");
        assert_eq!(stats.triangles, 2 * cells * cells, "{spec}");
        assert_eq!(stats.vertices, (cells + 1) * (cells + 1), "{spec}");
        let terrain = &scene.meshes[0];
        assert_eq!(terrain.name, "terrain");
        // Every vertex is a corner of its neighbours' triangles too: one smooth surface.
        let mut uses = vec![0u32; terrain.vertices.len()];
        for &index in terrain.indices.iter() {
            uses[index as usize] += 1;
        }
        let interior = (cells - 1) * (cells - 1);
        assert_eq!(uses.iter().filter(|&&n| n == 6).count(), interior, "{spec}");
        for vertex in terrain.vertices.iter() {
            let [x, y, z] = vertex.normal;
            assert!(((x * x + y * y + z * z).sqrt() - 1.0).abs() < 1e-5 && y > 0.0);
        }
        let (min, max) = (scene.bounds.min, scene.bounds.max);
        assert_eq!((min.x, min.z, max.x, max.z), (-50.0, -50.0, 50.0, 50.0));
        assert!(min.y >= 0.0 && max.y < 12.9, "{spec}: {min} {max}");
        assert_eq!(lights(&scene), (1, 4, 0), "{spec}");
    }
}

#[test]
fn one_terrain_seed_is_one_landscape_at_every_size() {
    let coarse = builtin("builtin:terrain?cells=4&seed=3");
    let fine = builtin("builtin:terrain?cells=8&seed=3");
    let (coarse, fine) = (&coarse.meshes[0].vertices, &fine.meshes[0].vertices);
    for j in 0..5 {
        for i in 0..5 {
            let (a, b) = (coarse[j * 5 + i], fine[2 * j * 9 + 2 * i]);
            assert_eq!(a.position, b.position, "({i}, {j})");
        }
    }
    let other = builtin("builtin:terrain?cells=4&seed=4");
    assert_ne!(other.meshes[0].vertices, *coarse);
}

#[test]
fn city_has_one_mesh_per_building_on_a_ground_plane() {
    for (spec, blocks) in [
        ("builtin:city?blocks=1", 1),
        ("builtin:city?blocks=3", 3),
        ("builtin:city", 32),
    ] {
        let scene = builtin(spec);
        let stats = scene.stats();
        assert_eq!(stats.meshes, blocks * blocks + 1, "{spec}");
        assert_eq!(stats.triangles, 12 * blocks * blocks + 2, "{spec}");
        assert_eq!(stats.materials, 5, "{spec}");
        assert_eq!(lights(&scene), (1, 4, 0), "{spec}");
        assert_eq!(scene.meshes[0].name, "ground");
        let block = 100.0 / blocks as f64;
        for (k, building) in scene.meshes[1..].iter().enumerate() {
            let (row, column) = (k / blocks, k % blocks);
            assert_eq!(building.name, format!("building {row},{column}"));
            assert_eq!(building.triangle_count(), 12);
            // Inside its block, standing on the ground, at most 30 tall.
            let bounds = building.world_bounds().unwrap();
            let corner = |i: usize| -50.0 + i as f64 * block;
            assert!(bounds.min.x > corner(column) && bounds.max.x < corner(column + 1));
            assert!(bounds.min.z > corner(row) && bounds.max.z < corner(row + 1));
            assert!(bounds.min.y.abs() < 1e-9 && bounds.max.y <= 30.0 + 1e-9);
        }
    }
}

#[test]
fn scale_scenes_are_bit_identical_for_one_spec_and_change_with_the_seed() {
    for (spec, reseeded) in [(
        "builtin:terrain?cells=50&seed=9",
        "builtin:terrain?cells=50&seed=10",
    )] {
        let (a, b) = (builtin(spec), builtin(spec));
        assert_eq!(a, b, "{spec}");
        for (ma, mb) in a.meshes.iter().zip(&b.meshes) {
            let bytes =
                |m: &rgraph_scene::Mesh| bytemuck::cast_slice::<_, u8>(&m.vertices).to_vec();
            assert_eq!(bytes(ma), bytes(mb), "{spec}: {}", ma.name);
            assert_eq!(ma.transform.to_cols_array(), mb.transform.to_cols_array());
        }
        assert_ne!(builtin(reseeded).meshes, a.meshes, "{reseeded}");
    }
}

/// What `cells` past the scene limit is told.
const CELLS_RANGE: &str = "a whole number from 1 to 7326 (cells per side of the heightfield, 2 \
     triangles each (default 224: 100,352 triangles; at most 7326: 107,340,552 \
     triangles in 4,294,442,824 bytes of vertices, indices and mesh, the most that fit the 4 \
     GiB scene limit))";

#[test]
fn sizes_past_the_scene_limit_are_refused_before_anything_is_built() {
    for (spec, message) in [
        (
            "builtin:terrain?cells=7327",
            format!("builtin:terrain: `cells=7327`: {CELLS_RANGE}"),
        ),
        (
            "builtin:terrain?cells=4294967295",
            format!("builtin:terrain: `cells=4294967295`: {CELLS_RANGE}"),
        ),
        (
            "builtin:city?blocks=1024",
            "builtin:city: `blocks=1024`: a whole number from 1 to 1023 (blocks per side, one \
             building each, each building its own mesh (default 32: 1,024 buildings; at most \
             1023: 1,046,529 buildings and the ground, the most within the scene \
             limit of 1,048,576 meshes))"
                .to_owned(),
        ),
    ] {
        let start = Instant::now();
        let (result, bytes) = allocated_by(|| Scene::load(spec));
        let elapsed = start.elapsed();
        let error = result.unwrap_err();
        assert!(
            matches!(error, SceneError::BuiltinParameter { .. }),
            "{error:?}"
        );
        assert_eq!(error.to_string(), message);
        // The error's own strings; the scenes asked for would have taken 4 GiB.
        assert!(
            bytes < 16 << 10,
            "{spec}: {bytes} bytes allocated before failing"
        );
        assert!(elapsed < Duration::from_secs(1), "{spec}: {elapsed:?}");
    }
    // The count sees what a scene allocates: a terrain of 100 cells, at least its vertices.
    let (_, bytes) = allocated_by(|| builtin("builtin:terrain?cells=100"));
    assert!(bytes > 101 * 101 * 56, "{bytes}");
}

#[test]
fn a_scale_scene_of_size_zero_is_an_error_naming_the_parameter() {
    let message = |spec: &str| Scene::load(spec).unwrap_err().to_string();
    assert_eq!(
        message("builtin:terrain?cells=0"),
        format!("builtin:terrain: `cells=0`: {CELLS_RANGE}")
    );
    assert!(message("builtin:terrain?size=3").contains("this scene takes: cells, seed"));
    assert!(message("builtin:city?blocks=0&seed=2")
        .starts_with("builtin:city: `blocks=0`: a whole number from 1 to 1023 (blocks per side"));
    assert!(message("builtin:city?streets=3").contains("this scene takes: blocks, seed"));
}
