//! EXT_mesh_gpu_instancing: instances place copies of a node's mesh where their transforms
//! say, count against the mesh limit before anything is read, and bad instance accessors
//! are errors naming the file, the node and the attribute.

use crate::allocations::allocated_by;
use crate::common;

use common::{temp_dir, Gltf, SHORT};
use std::sync::Arc;

use glam::{DMat4, DQuat, DVec3};
use rgraph_scene::{Scene, SceneError, MAX_MESHES};
use serde_json::{json, Value};

const EXTENSION: &str = "EXT_mesh_gpu_instancing";

/// A triangle mesh (0,0,0), (1,0,0), (0,1,0) of two primitives (the second a copy of the
/// first) placed by a root node with `node` fields and the extension's `attributes`;
/// `required` lists the extension in `extensionsRequired` too.
fn instanced(gltf: &mut Gltf, node: Value, attributes: Value, required: bool) {
    gltf.json["extensionsUsed"] = json!([EXTENSION]);
    if required {
        gltf.json["extensionsRequired"] = json!([EXTENSION]);
    }
    let positions = gltf.floats(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
    let primitive = json!({ "attributes": { "POSITION": positions } });
    let mesh = gltf.push(
        "meshes",
        json!({ "name": "tri", "primitives": [primitive.clone(), primitive] }),
    );
    let mut node = node;
    node["mesh"] = json!(mesh);
    node["name"] = json!("forest");
    node["extensions"] = json!({ EXTENSION: { "attributes": attributes } });
    gltf.root(node);
}

fn load(test: &str, gltf: &Gltf) -> (std::path::PathBuf, Result<Scene, SceneError>) {
    let path = temp_dir(test).join("scene.gltf");
    gltf.write_embedded(&path);
    let loaded = Scene::from_gltf(&path);
    (path, loaded)
}

#[test]
fn three_instances_are_placed_where_their_transforms_say() {
    let mut gltf = Gltf::default();
    let translations = gltf.floats(&[[0.0, 0.0, 0.0], [5.0, 0.0, 0.0], [0.0, 5.0, 0.0]]);
    // Normalized SHORT, as the extension allows: identity, 90° about +Z, 180° about +X.
    let h = (32767.0 * std::f64::consts::FRAC_1_SQRT_2).round() as i16;
    let rotations: Vec<u8> = [0, 0, 0, 32767, 0, 0, h, h, 32767, 0, 0, 0]
        .iter()
        .flat_map(|v: &i16| v.to_le_bytes())
        .collect();
    let rotations = gltf.accessor(&rotations, SHORT, 3, "VEC4", true);
    let scales = gltf.floats(&[[1.0, 1.0, 1.0], [1.0, 1.0, 1.0], [1.0, 2.0, 1.0]]);
    instanced(
        &mut gltf,
        json!({ "translation": [10.0, 0.0, 0.0], "scale": [2.0, 2.0, 2.0] }),
        json!({ "TRANSLATION": translations, "ROTATION": rotations, "SCALE": scales, "_ID": 0 }),
        true,
    );
    let (path, loaded) = load("instances_placed", &gltf);
    let scene = loaded.unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    // Two primitives, three instances each (primitive by primitive).
    assert_eq!(scene.meshes.len(), 6);
    let node = DMat4::from_scale_rotation_translation(
        DVec3::splat(2.0),
        DQuat::IDENTITY,
        DVec3::new(10.0, 0.0, 0.0),
    );
    let instances = [
        DMat4::IDENTITY,
        DMat4::from_rotation_translation(
            DQuat::from_rotation_z(std::f64::consts::FRAC_PI_2),
            DVec3::new(5.0, 0.0, 0.0),
        ),
        DMat4::from_scale_rotation_translation(
            DVec3::new(1.0, 2.0, 1.0),
            DQuat::from_rotation_x(std::f64::consts::PI),
            DVec3::new(0.0, 5.0, 0.0),
        ),
    ];
    // The quantized rotation's step, 1/32767, is the tolerance.
    for (mesh, instance) in scene.meshes.iter().zip(instances.iter().cycle()) {
        let expected = node * *instance;
        assert!(
            mesh.transform.abs_diff_eq(expected, 1e-4),
            "{}: {} vs {expected}",
            mesh.name,
            mesh.transform
        );
    }
    // Where the vertices end up: the node doubles and moves by +10 x what each instance
    // places. Instance 1: (1,0,0) turns to (0,1,0), moves to (5,1,0), lands at (20,2,0).
    // Instance 2: (0,1,0) doubles in y, turns to (0,-2,0), moves to (0,3,0): (10,6,0).
    let bounds: Vec<_> = scene.meshes[..3]
        .iter()
        .map(|m| m.world_bounds().unwrap())
        .collect();
    let expected = [
        ([10.0, 0.0, 0.0], [12.0, 2.0, 0.0]),
        ([18.0, 0.0, 0.0], [20.0, 2.0, 0.0]),
        ([10.0, 6.0, 0.0], [12.0, 10.0, 0.0]),
    ];
    for (got, (min, max)) in bounds.iter().zip(expected) {
        assert!(
            got.min.abs_diff_eq(DVec3::from(min), 1e-3)
                && got.max.abs_diff_eq(DVec3::from(max), 1e-3),
            "{got:?} vs {min:?}..{max:?}"
        );
    }
    // The instances of a primitive share its geometry: one array, not three copies. The
    // two primitives, equal in the file, are two geometries.
    for instances in scene.meshes.chunks(3) {
        for mesh in &instances[1..] {
            assert!(Arc::ptr_eq(&mesh.vertices, &instances[0].vertices));
            assert!(Arc::ptr_eq(&mesh.indices, &instances[0].indices));
        }
    }
    assert!(!Arc::ptr_eq(
        &scene.meshes[0].vertices,
        &scene.meshes[3].vertices
    ));
}

#[test]
fn instances_past_the_mesh_limit_are_refused_before_they_are_read() {
    // 524,289 instances of a mesh of two primitives: 1,048,578 meshes. The accessor has no
    // buffer view (all zeros but one sparse value), so the file is tiny while reading it
    // would take 12 MB, and building it far more.
    let count = MAX_MESHES as usize / 2 + 1;
    let mut gltf = Gltf::default();
    let index = gltf.view(&0u32.to_le_bytes());
    let value = gltf.view(&[0u8; 12]);
    let translations = gltf.push(
        "accessors",
        json!({ "componentType": 5126, "count": count, "type": "VEC3", "sparse": {
            "count": 1,
            "indices": { "bufferView": index, "componentType": 5125 },
            "values": { "bufferView": value },
        } }),
    );
    instanced(
        &mut gltf,
        json!({}),
        json!({ "TRANSLATION": translations }),
        false,
    );
    let path = temp_dir("instances_limit").join("scene.gltf");
    gltf.write_embedded(&path);
    let (loaded, bytes) = allocated_by(|| Scene::from_gltf(&path));
    let error = loaded.expect_err("too many meshes");
    assert!(
        matches!(
            error,
            SceneError::TooManyMeshes {
                count: 1_048_578,
                ..
            }
        ),
        "{error}"
    );
    assert!(bytes < 1 << 20, "{bytes} bytes allocated before failing");
}

#[test]
fn instancing_needs_no_warning_and_may_be_required() {
    let mut gltf = Gltf::default();
    let translations = gltf.floats(&[[0.0, 0.0, 0.0], [2.0, 0.0, 0.0]]);
    instanced(
        &mut gltf,
        json!({}),
        json!({ "TRANSLATION": translations }),
        true,
    );
    let (path, loaded) = load("instancing_required", &gltf);
    let scene = loaded.unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    assert_eq!(scene.meshes.len(), 4);
    assert_eq!(scene.meshes[1].transform.w_axis.x, 2.0);
}

#[test]
fn bad_instance_accessors_are_errors_naming_node_and_attribute() {
    // A name, the attributes it writes, what is wrong with them.
    type Case = (&'static str, fn(&mut Gltf) -> Value, &'static str);
    let cases: [Case; 5] = [
        (
            "count",
            |gltf| {
                let t = gltf.floats(&[[0.0f32; 3]; 3]);
                let s = gltf.floats(&[[0.0f32; 3]; 2]);
                json!({ "TRANSLATION": t, "SCALE": s })
            },
            "SCALE: accessor 1 has 2 elements, but TRANSLATION has 3: every instance \
             attribute of a node must have the same count",
        ),
        (
            "type",
            |gltf| {
                let t = gltf.floats(&[[0.0f32; 4]; 2]);
                json!({ "TRANSLATION": t })
            },
            "TRANSLATION: accessor 0 is VEC4 of FLOAT; the extension allows VEC3 of FLOAT",
        ),
        (
            "component",
            |gltf| {
                let r = gltf.accessor(&[0; 8], common::UNSIGNED_BYTE, 2, "VEC4", true);
                json!({ "ROTATION": r })
            },
            "ROTATION: accessor 0 is VEC4 of normalized UNSIGNED_BYTE; the extension allows \
             VEC4 of FLOAT or normalized BYTE or normalized SHORT",
        ),
        (
            "index",
            |_| json!({ "SCALE": 7 }),
            "SCALE: 7 is not an accessor index (the file has 1 accessors)",
        ),
        (
            "none",
            |_| json!({ "_ID": 0 }),
            "attributes: names none of TRANSLATION, ROTATION and SCALE, so the number of \
             instances is undefined",
        ),
    ];
    for (test, attributes, reason) in cases {
        let mut gltf = Gltf::default();
        let attributes = attributes(&mut gltf);
        instanced(&mut gltf, json!({}), attributes, false);
        let (path, loaded) = load(&format!("instances_bad_{test}"), &gltf);
        let error = loaded.expect_err(test);
        assert!(
            matches!(error, SceneError::InvalidInstances { .. }),
            "{test}: {error:?}"
        );
        assert_eq!(
            error.to_string(),
            format!(
                "{}: node 0 \"forest\": EXT_mesh_gpu_instancing {reason}",
                path.display()
            ),
            "{test}"
        );
    }
}

#[test]
fn non_finite_instance_values_are_errors_naming_the_instance() {
    let mut gltf = Gltf::default();
    let scales = gltf.floats(&[[1.0, 1.0, 1.0], [f32::INFINITY, 1.0, 1.0]]);
    instanced(&mut gltf, json!({}), json!({ "SCALE": scales }), false);
    let (path, loaded) = load("instances_non_finite", &gltf);
    assert_eq!(
        loaded.expect_err("infinite scale").to_string(),
        format!(
            "{}: node 0 \"forest\": EXT_mesh_gpu_instancing SCALE: instance 1 is [inf, 1.0, \
             1.0], not finite",
            path.display()
        )
    );
}
