//! glTF skins and morph targets: loaded into the scene's deformations, posed at rest and
//! by animations (joints and morph weights, sampled STEP, LINEAR and CUBICSPLINE),
//! deformed on the CPU to where glTF puts each vertex, bounded wherever they go, and bad
//! skins and morph targets refused with errors naming the file, the mesh or skin and the
//! accessor.

use crate::common::deformed::{
    bent_strip, eight_joint_strip, eight_weights, morphed_quad, EIGHT_JOINTS,
};
use crate::common::{temp_dir, Gltf, UNSIGNED_SHORT};
use glam::{DMat4, DQuat, DVec3, Vec3};
use rgraph_scene::{joints_in_object_space, Pose, Scene, SceneError};
use serde_json::json;

fn load(test: &str, gltf: &Gltf) -> Result<Scene, SceneError> {
    let path = temp_dir(test).join("scene.gltf");
    gltf.write_embedded(&path);
    Scene::from_gltf(&path)
}

/// Mesh 0's world positions and normals in `pose`, deformed on the CPU.
fn deformed(scene: &Scene, pose: &Pose) -> Vec<(DVec3, DVec3)> {
    let d = &scene.deformations[0];
    let transform = pose.transforms[d.mesh];
    let joints = match &d.skin {
        Some(skin) => joints_in_object_space(transform, &pose.skins[skin.skin]),
        None => Vec::new(),
    };
    let vertices = d.deform(
        &scene.meshes[d.mesh].vertices,
        &joints,
        &pose.morph_weights[0],
    );
    let normal_matrix = glam::DMat3::from_mat4(transform).inverse().transpose();
    (vertices.iter())
        .map(|v| {
            let p = transform.transform_point3(Vec3::from_array(v.position).as_dvec3());
            let n = (normal_matrix * Vec3::from_array(v.normal).as_dvec3()).normalize();
            (p, n)
        })
        .collect()
}

fn assert_near(actual: DVec3, expected: DVec3, what: &str) {
    assert!(
        actual.abs_diff_eq(expected, 1e-5),
        "{what}: {actual} differs from {expected}"
    );
}

#[test]
fn a_skinned_strip_bends_where_its_joints_put_it_at_rest_and_animated() {
    let scene = load("skinned", &bent_strip()).expect("loads");
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    assert_eq!(scene.skins.len(), 1);
    assert_eq!(scene.skins[0].name, "skin 0 \"arm\"");
    assert_eq!(scene.deformations.len(), 1);
    let rest = deformed(&scene, &scene.rest_pose());
    let h = std::f64::consts::FRAC_1_SQRT_2;
    for (i, y) in [-0.25, 0.25].into_iter().enumerate() {
        // The left end stays at x = 0 (the skinned node's own translation is ignored).
        assert_near(rest[i].0, DVec3::new(0.0, y, 0.0), "left end");
        assert_near(rest[i].1, DVec3::Z, "left end's normal");
        // The middle, half on each joint: joint 1 leaves its own origin where it is.
        assert_near(rest[2 + i].0, DVec3::new(1.0, y, 0.0), "middle");
        // Half of +Z and half of +Z turned 90° about +Y (+X): the cofactor of the blend.
        assert_near(rest[2 + i].1, DVec3::new(h, 0.0, h), "middle's normal");
        // The right end turned 90° about +Y around x = 1: (1, 0, 0) from the joint
        // becomes (0, 0, -1).
        assert_near(rest[4 + i].0, DVec3::new(1.0, y, -1.0), "right end");
        assert_near(rest[4 + i].1, DVec3::X, "right end's normal");
    }
    // Animated: 45° at 0.5 s.
    let id = scene.find_animation("bend").expect("the animation");
    let half = deformed(&scene, &scene.animated_pose(id, 0.5));
    assert_near(
        half[5].0,
        DVec3::new(1.0 + h, 0.25, -h),
        "right end at 0.5 s",
    );
    // The bounds hold the strip at rest and over the animation.
    for (p, _) in rest.iter().chain(&half) {
        let (min, max) = (scene.bounds.min, scene.bounds.max);
        assert!(
            p.cmpge(min - 1e-9).all() && p.cmple(max + 1e-9).all(),
            "{p} outside {min}..{max}"
        );
    }
}

/// Eight influences per vertex: JOINTS_1 and WEIGHTS_1 load as the second set, and the
/// CPU deformation blends all eight joints, each vertex at the sum of its weights times
/// its joints' transforms of its rest position (joints 4 to 7 carry half the weight), at
/// rest and with joint 5 turned from 10° to 20° (0.5 s).
#[test]
fn eight_influences_load_from_both_sets_and_all_eight_deform() {
    let scene = load("eight-joints", &eight_joint_strip()).expect("loads");
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    let skin = scene.deformations[0].skin.as_ref().expect("skinned");
    let second = skin
        .second
        .as_ref()
        .expect("JOINTS_1 and WEIGHTS_1 are read");
    assert_eq!(
        (skin.first.joints[0], second.joints[0]),
        ([0, 1, 2, 3], [4, 5, 6, 7])
    );
    let id = scene.find_animation("sway").expect("the animation");
    for (time, degrees) in [(None, 10.0f64), (Some(0.5), 20.0)] {
        let pose = time.map_or_else(|| scene.rest_pose(), |t| scene.animated_pose(id, t));
        let got = deformed(&scene, &pose);
        let joint = |k: usize| {
            let (translation, rotation) = EIGHT_JOINTS[k];
            let rotation = match k {
                5 => DQuat::from_rotation_z(degrees.to_radians()),
                _ => DQuat::from_array(rotation.map(f64::from)),
            };
            DMat4::from_rotation_translation(rotation, Vec3::from_array(translation).as_dvec3())
        };
        for (v, vertex) in scene.meshes[0].vertices.iter().enumerate() {
            let p = Vec3::from_array(vertex.position).as_dvec3();
            let expected: DVec3 = (eight_weights(v / 2).iter().enumerate())
                .map(|(k, &w)| joint(k).transform_point3(p) * f64::from(w))
                .sum();
            assert_near(got[v].0, expected, &format!("vertex {v} at {degrees}°"));
        }
    }
}

/// Sets past the second (JOINTS_2) are a warning naming the mesh and primitive; a set
/// with joints but no weights is an error; and weights of both sets not summing to 1
/// are an error showing both.
#[test]
fn a_third_influence_set_warns_and_a_half_set_or_a_bad_sum_is_refused() {
    let mut gltf = eight_joint_strip();
    let attributes = &mut gltf.json["meshes"][0]["primitives"][0]["attributes"];
    attributes["JOINTS_2"] = attributes["JOINTS_1"].clone();
    attributes["WEIGHTS_2"] = attributes["WEIGHTS_1"].clone();
    let scene = load("third-set", &gltf).expect("loads");
    assert_eq!(
        scene.warnings,
        [
            "mesh 0 \"eight\" primitive 0: JOINTS_2 and WEIGHTS_2 are ignored: each vertex \
          keeps its first eight joints, their weights renormalised"
        ]
    );
    assert!(scene.deformations[0]
        .skin
        .as_ref()
        .unwrap()
        .second
        .is_some());

    let mut gltf = eight_joint_strip();
    let attributes = &mut gltf.json["meshes"][0]["primitives"][0]["attributes"];
    attributes.as_object_mut().unwrap().remove("WEIGHTS_1");
    expect_error(
        "half-set",
        &gltf,
        "mesh 0 \"eight\" primitive 0: has only one of JOINTS_1 and WEIGHTS_1: a set of \
         joints needs its weights",
    );

    let mut gltf = eight_joint_strip();
    let zeros = gltf.floats(&[[0.0f32; 4]; 18]);
    gltf.json["meshes"][0]["primitives"][0]["attributes"]["WEIGHTS_1"] = json!(zeros);
    let weights_0 = &gltf.json["meshes"][0]["primitives"][0]["attributes"]["WEIGHTS_0"];
    expect_error(
        "eight-sum",
        &gltf,
        &format!(
            "mesh 0 \"eight\" primitive 0: WEIGHTS_0 accessor {weights_0}: vertex 0 has \
             weights [0.05, 0.1, 0.15, 0.2] and [0.0, 0.0, 0.0, 0.0] (WEIGHTS_1 accessor \
             {zeros}), summing to 0.5: a vertex's weights are non-negative and sum to 1 \
             (within 0.05)"
        ),
    );
}

#[test]
fn a_morph_weight_animation_is_sampled_at_three_times() {
    let scene = load("morph-linear", &morphed_quad("LINEAR")).expect("loads");
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    assert_eq!(scene.rest_pose().morph_weights, vec![vec![0.25]]);
    let id = scene.find_animation("grow").expect("the animation");
    // Keys 0, 1, 0.5 at 0, 1 and 2 s; after the last key its value holds.
    for (time, weight) in [(0.5, 0.5), (1.5, 0.75), (3.0, 0.5)] {
        let pose = scene.animated_pose(id, time);
        assert_eq!(pose.morph_weights, vec![vec![weight as f32]], "t = {time}");
        let top = deformed(&scene, &pose)[2];
        assert_near(
            top.0,
            DVec3::new(1.0, 1.0 + 0.5 * weight, 0.0),
            &format!("t = {time}"),
        );
        let normal = DVec3::new(0.5 * weight, 0.0, 1.0).normalize();
        assert_near(top.1, normal, &format!("the normal at t = {time}"));
    }
    // STEP holds the previous key's; CUBICSPLINE with zero tangents eases: at s = 0.5,
    // halfway in value (3s² - 2s³ = 0.5).
    let step = load("morph-step", &morphed_quad("STEP")).expect("loads");
    assert_eq!(step.animated_pose(id, 1.5).morph_weights, vec![vec![1.0]]);
    let cubic = load("morph-cubic", &morphed_quad("CUBICSPLINE")).expect("loads");
    let eased = cubic.animated_pose(id, 0.25).morph_weights[0][0];
    // s = 0.25: 3s² - 2s³ = 0.15625.
    assert!(
        (eased - 0.15625).abs() < 1e-6,
        "CUBICSPLINE at 0.25 s: {eased}"
    );
}

/// Points and lines are not deformed: the strip drawn as POINTS, under its skinned node,
/// warns that the skin is ignored and keeps the node's transform; with a morph target
/// too, the warning names both.
#[test]
fn skinned_or_morphed_points_warn_that_they_are_not_deformed() {
    let mut gltf = bent_strip();
    gltf.json["meshes"][0]["primitives"][0]["mode"] = json!(0);
    let scene = load("skinned-points", &gltf).expect("loads");
    assert_eq!(
        scene.warnings,
        [
            "mesh 0 \"strip\" primitive 0: points and lines are not deformed: skin 0 \"arm\" \
          (its JOINTS_0 and WEIGHTS_0) is ignored, and they follow the transform of node 2 \
          \"strip\""
        ]
    );
    assert!(scene.deformations.is_empty());
    let moved = DVec3::new(5.0, 0.0, 0.0);
    assert_eq!(scene.points_lines[0].transform.w_axis.truncate(), moved);
    let lift = gltf.floats(&[[0.0, 1.0, 0.0]; 6]);
    gltf.json["meshes"][0]["primitives"][0]["targets"] = json!([{ "POSITION": lift }]);
    let scene = load("skinned-morphed-points", &gltf).expect("loads");
    assert!(
        scene.warnings[0].contains(
            "skin 0 \"arm\" (its JOINTS_0 and WEIGHTS_0) and its 1 morph targets are ignored"
        ),
        "{:?}",
        scene.warnings
    );
}

fn expect_error(test: &str, gltf: &Gltf, expected: &str) {
    let path = temp_dir(test).join("scene.gltf");
    gltf.write_embedded(&path);
    let error = Scene::from_gltf(&path).expect_err("refused").to_string();
    let expected = format!("{}: {expected}", path.display());
    assert_eq!(error, expected);
}

/// Writes `joints` as the strip's JOINTS_0 (a new accessor).
fn with_joints(gltf: &mut Gltf, joints: [[u16; 4]; 6]) -> usize {
    let bytes: Vec<u8> = joints
        .iter()
        .flatten()
        .flat_map(|j| j.to_le_bytes())
        .collect();
    let accessor = gltf.accessor(&bytes, UNSIGNED_SHORT, 6, "VEC4", false);
    gltf.json["meshes"][0]["primitives"][0]["attributes"]["JOINTS_0"] = json!(accessor);
    accessor
}

#[test]
fn bad_skins_are_errors_naming_the_file_the_mesh_or_skin_and_the_accessor() {
    let mut gltf = bent_strip();
    let accessor = with_joints(
        &mut gltf,
        [[0, 1, 0, 0], [0, 2, 0, 0], [0; 4], [0; 4], [0; 4], [0; 4]],
    );
    expect_error(
        "joint-range",
        &gltf,
        &format!(
            "mesh 0 \"strip\" primitive 0: JOINTS_0 accessor {accessor}: vertex 1 names joint 2, \
             but skin 0 has 2 joints"
        ),
    );

    let mut gltf = bent_strip();
    let weights = gltf.floats(&[[0.5, 0.0, 0.0, 0.0]; 6]);
    gltf.json["meshes"][0]["primitives"][0]["attributes"]["WEIGHTS_0"] = json!(weights);
    expect_error(
        "weight-sum",
        &gltf,
        &format!(
            "mesh 0 \"strip\" primitive 0: WEIGHTS_0 accessor {weights}: vertex 0 has weights \
             [0.5, 0.0, 0.0, 0.0], summing to 0.5: a vertex's weights are non-negative and sum \
             to 1 (within 0.05)"
        ),
    );

    let mut gltf = bent_strip();
    let short = gltf.floats(&[[1.0, 0.0, 0.0, 0.0]; 5]);
    gltf.json["meshes"][0]["primitives"][0]["attributes"]["WEIGHTS_0"] = json!(short);
    expect_error(
        "weight-count",
        &gltf,
        &format!(
            "mesh 0 \"strip\" primitive 0: WEIGHTS_0 accessor {short}: has 5 elements, but the \
             primitive has 6 vertices (POSITION's count)"
        ),
    );

    // A joint outside the loaded scene: node 1 taken out of the hierarchy.
    let mut gltf = bent_strip();
    gltf.json["nodes"][0]["children"] = json!([]);
    expect_error(
        "joint-outside",
        &gltf,
        "skin 0 \"arm\": joint node 1 \"bend\" is not in the loaded scene, so nothing could pose it",
    );

    let mut gltf = bent_strip();
    let matrices = gltf.floats(&[[1.0, 0.0, 0.0]]);
    gltf.json["skins"][0]["inverseBindMatrices"] = json!(matrices);
    expect_error(
        "inverse-binds",
        &gltf,
        &format!(
            "skin 0 \"arm\": inverseBindMatrices accessor {matrices}: is VEC3 of FLOAT, but \
             inverse bind matrices are MAT4 of FLOAT"
        ),
    );
}

#[test]
fn bad_morph_targets_are_errors_naming_the_file_the_mesh_and_the_accessor() {
    let mut gltf = morphed_quad("LINEAR");
    let short = gltf.floats(&[[0.0, 1.0, 0.0]; 3]);
    gltf.json["meshes"][0]["primitives"][0]["targets"][0]["POSITION"] = json!(short);
    expect_error(
        "target-count",
        &gltf,
        &format!(
            "mesh 0 \"quad\" primitive 0: morph target 0 POSITION accessor {short}: has 3 \
             elements, but the primitive has 4 vertices (POSITION's count)"
        ),
    );

    let mut gltf = morphed_quad("LINEAR");
    gltf.json["meshes"][0]["weights"] = json!([0.25, 0.5]);
    expect_error(
        "default-weights",
        &gltf,
        "mesh 0 \"quad\" primitive 0: has 1 morph targets, but its default weights (the \
         node's, else the mesh's) are [0.25, 0.5]: one finite weight per target",
    );

    // A weights channel with two weights per key for one target.
    let mut gltf = morphed_quad("LINEAR");
    let output = gltf.floats(&[[0.0], [1.0], [0.5], [0.0], [1.0], [0.5]]);
    gltf.json["animations"][0]["samplers"][0]["output"] = json!(output);
    let input = &gltf.json["animations"][0]["samplers"][0]["input"];
    expect_error(
        "weights-channel",
        &gltf,
        &format!(
            "animation 0 \"grow\" channel 0: output accessor {output} has 6 elements, but its \
             input accessor {input} has 3 key times and it needs one per key time, times the mesh's 1 \
             morph targets"
        ),
    );
}
