//! glTF animations: an animated node is where its sampler puts it (STEP, LINEAR,
//! CUBICSPLINE, rotations along the shorter arc), the bounds hold the motion, and bad
//! samplers are errors naming the file, the animation, the channel and the accessor.

use crate::allocations::allocated_by;
use crate::common::{temp_dir, Gltf, FLOAT, UNSIGNED_SHORT};
use glam::{DMat4, DVec3};
use rgraph_scene::Interpolation::{CubicSpline, Linear};
use rgraph_scene::{Scene, SceneError};
use serde_json::json;

/// A triangle (0,0,0), (1,0,0), (0,1,0) placed by root node 0, "mover".
fn mover() -> Gltf {
    let mut gltf = Gltf::default();
    let positions = gltf.floats(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
    let mesh = gltf.push(
        "meshes",
        json!({ "name": "tri", "primitives": [{ "attributes": { "POSITION": positions } }] }),
    );
    gltf.root(json!({ "name": "mover", "mesh": mesh }));
    gltf
}

fn load(test: &str, gltf: &Gltf) -> (std::path::PathBuf, Result<Scene, SceneError>) {
    let path = temp_dir(test).join("scene.gltf");
    gltf.write_embedded(&path);
    let loaded = Scene::from_gltf(&path);
    (path, loaded)
}

/// The mesh's transform with animation `name` at each of `times`.
fn transforms_at(scene: &Scene, name: &str, times: &[f64]) -> Vec<DMat4> {
    let id = scene.find_animation(name).expect("the animation");
    times
        .iter()
        .map(|&t| scene.animated_pose(id, t).transforms[0])
        .collect()
}

fn assert_near(actual: DVec3, expected: DVec3, what: &str) {
    assert!(
        actual.abs_diff_eq(expected, 1e-5),
        "{what}: {actual} differs from {expected}"
    );
}

/// Where the mesh's origin is with animation `name` at each of `times`.
fn translations(scene: &Scene, name: &str, times: &[f64]) -> Vec<DVec3> {
    (transforms_at(scene, name, times).iter())
        .map(|m| m.w_axis.truncate())
        .collect()
}

#[test]
fn step_holds_each_key_until_the_next() {
    let mut gltf = mover();
    let values = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [3.0, 0.0, 0.0]];
    gltf.animation("hop", 0, "translation", "STEP", &[0.0, 1.0, 2.0], &values);
    let scene = load("step", &gltf).1.expect("loads");
    let at = translations(&scene, "hop", &[0.5, 1.5, 2.5]);
    assert_near(at[0], DVec3::ZERO, "t = 0.5, the first key's");
    assert_near(at[1], DVec3::X, "t = 1.5, the second key's");
    assert_near(at[2], DVec3::new(3.0, 0.0, 0.0), "t = 2.5, after the end");
}

#[test]
fn linear_blends_between_keys_and_clamps_outside_them() {
    let mut gltf = mover();
    let values = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [3.0, 2.0, 0.0]];
    gltf.animation(
        "slide",
        0,
        "translation",
        "LINEAR",
        &[0.0, 1.0, 2.0],
        &values,
    );
    let scene = load("linear", &gltf).1.expect("loads");
    let at = translations(&scene, "slide", &[-1.0, 0.25, 1.5]);
    assert_near(at[0], DVec3::ZERO, "t = -1, before the start");
    assert_near(at[1], DVec3::new(0.25, 0.0, 0.0), "t = 0.25");
    assert_near(at[2], DVec3::new(2.0, 1.0, 0.0), "t = 1.5");
}

#[test]
fn cubic_spline_is_hermite_with_tangents_scaled_by_the_interval() {
    let mut gltf = mover();
    // Keys at 0 and 2 (interval 2): value 0 leaving with tangent 1, value 4 arriving with
    // tangent 3. Per glTF: p(s) = (2s³-3s²+1)·v0 + 2(s³-2s²+s)·b0 + (-2s³+3s²)·v1 + 2(s³-s²)·a1.
    let values = [
        [9.0, 9.0, 9.0], // in-tangent of the first key: unused
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [3.0, 0.0, 0.0],
        [4.0, 0.0, 0.0],
        [9.0, 9.0, 9.0], // out-tangent of the last key: unused
    ];
    gltf.animation(
        "ease",
        0,
        "translation",
        "CUBICSPLINE",
        &[0.0, 2.0],
        &values,
    );
    let scene = load("cubic", &gltf).1.expect("loads");
    let at = translations(&scene, "ease", &[0.5, 1.0, 2.0]);
    // s = 0.25: 0.140625·2·1 + 0.15625·4 - 0.046875·2·3 = 0.625.
    assert_near(at[0], DVec3::new(0.625, 0.0, 0.0), "t = 0.5");
    // s = 0.5: 0.125·2·1 + 0.5·4 - 0.125·2·3 = 1.5.
    assert_near(at[1], DVec3::new(1.5, 0.0, 0.0), "t = 1");
    assert_near(at[2], DVec3::new(4.0, 0.0, 0.0), "t = 2, the last key");
}

#[test]
fn slerp_takes_the_shorter_arc_and_cubic_rotations_are_unit() {
    let mut gltf = mover();
    let h = std::f32::consts::FRAC_1_SQRT_2;
    // 90° about +Z written as its negation (-q is the same rotation): the shorter arc
    // passes 45°, the longer one -135°.
    let turn = [[0.0, 0.0, 0.0, 1.0], [0.0, 0.0, -h, -h]];
    gltf.animation("turn", 0, "rotation", "LINEAR", &[0.0, 1.0], &turn);
    let spline = [
        [0.0; 4],
        [0.0, 0.0, 0.0, 1.0],
        [0.0; 4],
        [0.0; 4],
        [0.0, 0.0, h, h],
        [0.0; 4],
    ];
    gltf.animation("spline", 0, "rotation", "CUBICSPLINE", &[0.0, 1.0], &spline);
    let scene = load("slerp", &gltf).1.expect("loads");
    let eighth = std::f64::consts::FRAC_1_SQRT_2;
    let x_at = |name, t| transforms_at(&scene, name, &[t])[0].transform_vector3(DVec3::X);
    assert_near(
        x_at("turn", 0.5),
        DVec3::new(eighth, eighth, 0.0),
        "slerp at 0.5",
    );
    let angle = 30f64.to_radians();
    let third = DVec3::new(angle.cos(), angle.sin(), 0.0);
    assert_near(x_at("turn", 1.0 / 3.0), third, "slerp at 1/3");
    // Zero tangents: s = 0.5 blends the keys half and half, normalised to 45°.
    assert_near(
        x_at("spline", 0.5),
        DVec3::new(eighth, eighth, 0.0),
        "cubic at 0.5",
    );
}

#[test]
fn a_child_moves_with_its_animated_parent_and_the_bounds_hold_the_motion() {
    let mut gltf = mover();
    let child = gltf.push(
        "nodes",
        json!({ "name": "child", "mesh": 0, "translation": [0.0, 5.0, 0.0] }),
    );
    gltf.json["nodes"][0]["children"] = json!([child]);
    let values = [[0.0, 0.0, 0.0], [10.0, 0.0, 0.0]];
    gltf.animation("carry", 0, "translation", "LINEAR", &[0.0, 1.0], &values);
    let scene = load("hierarchy", &gltf).1.expect("loads");
    assert_eq!(scene.meshes.len(), 2);
    let id = scene.find_animation("carry").expect("by name");
    assert_eq!(scene.find_animation("0").expect("by index"), id);
    assert_eq!(scene.animation(id).end, 1.0);
    let moved = scene.animated_pose(id, 0.5).transforms;
    assert_near(
        moved[1].w_axis.truncate(),
        DVec3::new(5.0, 5.0, 0.0),
        "the child",
    );
    let rest = scene.animated_pose(id, 0.0).transforms;
    let loaded: Vec<DMat4> = scene.meshes.iter().map(|m| m.transform).collect();
    assert_eq!(
        rest, loaded,
        "at its rest values the animation gives the loaded transforms"
    );
    assert_eq!(
        scene.bounds.max,
        DVec3::new(11.0, 6.0, 0.0),
        "the swept bounds"
    );
}

/// Points and lines hang in the node tree as meshes do: a POINTS primitive placed by a
/// child of the animated node moves with it, the pose's transform for it at rest is the
/// loaded one, and the bounds hold it wherever the animation takes it. A LINE_STRIP of one
/// vertex (no segment, dropped) comes first, so that the placements must be dropped with
/// the primitives they place.
#[test]
fn points_move_with_their_animated_node_and_the_bounds_hold_them() {
    let mut gltf = mover();
    let lone = gltf.floats(&[[0.0, 0.0, 0.0]]);
    let positions = gltf.floats(&[[0.0, 0.0, 0.0], [2.0, 0.0, 2.0]]);
    let points = gltf.push(
        "meshes",
        json!({ "name": "dots", "primitives": [
            { "attributes": { "POSITION": lone }, "mode": 3 },
            { "attributes": { "POSITION": positions }, "mode": 0 },
        ] }),
    );
    let child = gltf.push(
        "nodes",
        json!({ "name": "child", "mesh": points, "translation": [0.0, 5.0, 0.0] }),
    );
    gltf.json["nodes"][0]["children"] = json!([child]);
    let values = [[0.0, 0.0, 0.0], [10.0, 0.0, 0.0]];
    gltf.animation("carry", 0, "translation", "LINEAR", &[0.0, 1.0], &values);
    let scene = load("points-animated", &gltf).1.expect("loads");
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    assert_eq!(scene.points_lines.len(), 1);
    assert_eq!(scene.points_lines[0].name, "mesh 1 \"dots\" primitive 1");
    assert_eq!(
        scene.rest_pose().points_lines,
        [scene.points_lines[0].transform]
    );
    let id = scene.find_animation("carry").expect("the animation");
    for (time, x) in [(0.25, 4.5), (0.5, 7.0), (1.0, 12.0)] {
        let moved = scene.animated_pose(id, time).points_lines;
        assert_eq!(moved.len(), 1);
        let far = moved[0].transform_point3(DVec3::new(2.0, 0.0, 2.0));
        assert_near(
            far,
            DVec3::new(x, 5.0, 2.0),
            &format!("the point at {time} s"),
        );
    }
    assert_eq!(
        scene.animated_pose(id, 0.0).points_lines,
        scene.rest_pose().points_lines
    );
    assert_eq!(
        (scene.bounds.min, scene.bounds.max),
        (DVec3::ZERO, DVec3::new(12.0, 5.0, 2.0)),
        "the swept bounds"
    );
}

#[test]
fn an_unknown_animation_lists_the_scene_s_animations() {
    let mut gltf = mover();
    gltf.animation("hop", 0, "translation", "STEP", &[0.0], &[[0.0; 3]]);
    let scene = load("unknown", &gltf).1.expect("loads");
    let error = scene.find_animation("jump").expect_err("no such animation");
    let message = format!(
        "scene \"{}\" has no animation \"jump\" (its animations: 0 \"hop\")",
        scene.name
    );
    assert_eq!(error.to_string(), message);
    let still = Scene::load("builtin:spheres").expect("built in");
    assert_eq!(
        still.find_animation("0").expect_err("none").to_string(),
        "scene \"builtin:spheres\" has no animation \"0\" (its animations: none: the scene \
         has no animations)"
    );
}

/// Loads `gltf` and returns the error message, after the file's path and a colon.
fn error_of(test: &str, gltf: &Gltf) -> String {
    let (path, loaded) = load(test, gltf);
    let message = loaded.expect_err("an invalid animation").to_string();
    let prefix = format!("{}: ", path.display());
    message
        .strip_prefix(&prefix)
        .unwrap_or_else(|| panic!("{message} does not start with the file"))
        .to_owned()
}

#[test]
fn bad_samplers_are_errors_naming_the_animation_channel_and_accessor() {
    let mut gltf = mover();
    gltf.animation(
        "hop",
        0,
        "translation",
        "LINEAR",
        &[0.0, 1.0, 1.0],
        &[[0.0; 3]; 3],
    );
    assert_eq!(
        error_of("decreasing", &gltf),
        "animation 0 \"hop\" channel 0: input accessor 1: key time 2 (1) is not after key \
         time 1 (1): key times must be strictly increasing"
    );

    let mut gltf = mover();
    gltf.animation(
        "hop",
        0,
        "translation",
        "CUBICSPLINE",
        &[0.0, 1.0],
        &[[0.0; 3]; 2],
    );
    assert_eq!(
        error_of("cubic_count", &gltf),
        "animation 0 \"hop\" channel 0: output accessor 2 has 2 elements, but its input \
         accessor 1 has 2 key times and it needs three per key time (in-tangent, value, \
         out-tangent) for CUBICSPLINE"
    );

    let mut gltf = mover();
    gltf.animation("hop", 0, "scale", "LINEAR", &[0.0], &[[1.0; 4]]);
    assert_eq!(
        error_of("output_type", &gltf),
        "animation 0 \"hop\" channel 0: output accessor 2 is VEC4 of FLOAT, but a scale \
         must be VEC3 of FLOAT"
    );

    let mut gltf = mover();
    gltf.animation("hop", 0, "translation", "STEP", &[0.0], &[[0.0; 3]]);
    let times = gltf.accessor(&[0, 0], UNSIGNED_SHORT, 1, "SCALAR", false);
    gltf.json["animations"][0]["samplers"][0]["input"] = json!(times);
    assert_eq!(
        error_of("input_type", &gltf),
        "animation 0 \"hop\" channel 0: input accessor 3 is SCALAR of UNSIGNED_SHORT, but \
         key times must be SCALAR of FLOAT"
    );

    let mut gltf = mover();
    gltf.animation("hop", 0, "translation", "STEP", &[0.0], &[[0.0; 3]]);
    gltf.json["nodes"][0]["matrix"] = json!([1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]);
    assert_eq!(
        error_of("matrix", &gltf),
        "animation 0 \"hop\" channel 0: targets node 0 \"mover\", whose transform is a \
         matrix: glTF animates only nodes with translation, rotation and scale"
    );

    let mut gltf = mover();
    gltf.animation(
        "hop",
        0,
        "translation",
        "STEP",
        &[0.0],
        &[[f32::NAN, 0.0, 0.0]],
    );
    assert_eq!(
        error_of("not_finite", &gltf),
        "animation 0 \"hop\" channel 0: output accessor 2: value 0 is not finite"
    );
}

#[test]
fn counts_beyond_the_buffer_are_refused_before_anything_is_allocated() {
    let mut gltf = mover();
    gltf.animation("hop", 0, "translation", "STEP", &[0.0], &[[0.0; 3]]);
    // Four billion key times declared over a 4-byte view, and values to match.
    let count = 4_000_000_000u64;
    gltf.json["accessors"][1]["count"] = json!(count);
    let values = gltf.accessor(&[0; 12], FLOAT, 1, "VEC3", false);
    gltf.json["accessors"][values]["count"] = json!(count);
    gltf.json["animations"][0]["samplers"][0]["output"] = json!(values);
    let path = temp_dir("huge_count").join("scene.gltf");
    gltf.write_embedded(&path);
    let (loaded, bytes) = allocated_by(|| Scene::from_gltf(&path));
    let message = loaded.expect_err("counts past the view").to_string();
    assert_eq!(
        message,
        format!(
            "{}: animation 0 \"hop\" channel 0: input accessor 1: 4000000000 elements from \
             byte 0 with stride 4 overrun its 4 byte buffer view",
            path.display()
        )
    );
    assert!(bytes < 1 << 20, "loading allocated {bytes} bytes");

    // A count whose triple (CUBICSPLINE's values) overflows is refused, not wrapped.
    let mut gltf = mover();
    gltf.animation(
        "hop",
        0,
        "translation",
        "CUBICSPLINE",
        &[0.0],
        &[[0.0; 3]; 3],
    );
    gltf.json["accessors"][1]["count"] = json!(u64::MAX / 2);
    assert_eq!(
        error_of("overflow", &gltf),
        format!(
            "animation 0 \"hop\" channel 0: output accessor 2 has 3 elements, but its input \
             accessor 1 has {} key times and it needs three per key time (in-tangent, value, \
             out-tangent) for CUBICSPLINE",
            u64::MAX / 2
        )
    );
}

#[test]
fn the_animated_cubes_fixture_loads_one_channel_per_interpolation() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../tests/fixtures/AnimatedCubes/AnimatedCubes.gltf");
    let scene = Scene::from_gltf(&path).expect("the fixture loads");
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    let id = scene.find_animation("dance").expect("its animation");
    let dance = scene.animation(id);
    let kinds: Vec<_> = dance.channels.iter().map(|c| c.interpolation).collect();
    assert_eq!(kinds, [Linear, Linear, CubicSpline]);
    assert_eq!((dance.start, dance.end), (0.0, 2.0));
    // The moon (mesh 2: meshes follow the nodes depth first, and it is the green cube's
    // child) has turned with the cube by 90° about +Y at 0.5 s:
    // from 1.5 right of the cube to 1.5 behind it.
    let moon = scene.animated_pose(id, 0.5).transforms[2].w_axis.truncate();
    assert_near(moon, DVec3::new(0.0, 0.0, -3.5), "the moon at 0.5 s");
}
