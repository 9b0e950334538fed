//! Exact large worlds and values beyond what renders: node transforms are read as f64, and
//! transforms, camera planes and light values that overflow are errors naming the object,
//! never a silent empty frame. Missing images name the glTF file and the material.

use crate::common;

use common::{temp_dir, Gltf};
use rgraph_scene::{Light, LightKind, Scene, SceneError, DEFAULT_CUTOFF_ILLUMINANCE};
use serde_json::{json, Value};

/// A triangle whose node has `node_fields` (`translation`, `matrix`, ...), written as an
/// embedded `.gltf` and loaded.
fn triangle_with(
    test: &str,
    node_fields: Value,
) -> (std::path::PathBuf, Result<Scene, SceneError>) {
    let mut gltf = Gltf::default();
    gltf.triangle(None);
    for (key, value) in node_fields.as_object().unwrap() {
        gltf.json["nodes"][0][key] = value.clone();
    }
    let path = temp_dir(test).join("scene.gltf");
    gltf.write_embedded(&path);
    let loaded = Scene::from_gltf(&path);
    (path, loaded)
}

#[test]
fn translations_far_from_the_origin_are_read_exactly() {
    // f32 would give 1000000.3125 and 100000000 (steps of 1/16 and 8).
    for (x, y) in [(1_000_000.3, -0.7), (100_000_001.3, 2.1)] {
        let (path, loaded) =
            triangle_with("f64_translation", json!({ "translation": [x, y, 0.5] }));
        let scene = loaded.unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let t = scene.meshes[0].transform.w_axis;
        assert_eq!((t.x, t.y, t.z), (x, y, 0.5));
    }
    let matrix = [
        1.0,
        0.0,
        0.0,
        0.0,
        0.0,
        1.0,
        0.0,
        0.0,
        0.0,
        0.0,
        1.0,
        0.0,
        3e7 + 0.1,
        0.0,
        0.0,
        1.0,
    ];
    let (path, loaded) = triangle_with("f64_matrix", json!({ "matrix": matrix }));
    let scene = loaded.unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    assert_eq!(scene.meshes[0].transform.w_axis.x, 3e7 + 0.1);
}

#[test]
fn glb_translations_are_read_exactly_too() {
    let mut gltf = Gltf::default();
    gltf.triangle(None);
    gltf.json["nodes"][0]["translation"] = json!([1_000_000.3, 0.0, 0.0]);
    let path = temp_dir("f64_glb").join("scene.glb");
    gltf.write_glb(&path);
    let scene = Scene::from_gltf(&path).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene.meshes[0].transform.w_axis.x, 1_000_000.3);
}

#[test]
fn transforms_beyond_the_largest_coordinate_are_errors_naming_the_node() {
    for (fields, value) in [
        (
            json!({ "translation": [1e39, 0.0, 0.0], "name": "far" }),
            "1e39",
        ),
        (json!({ "scale": [1e39, 1.0, 1.0], "name": "far" }), "1e39"),
        (
            json!({ "translation": [0.0, 2e12, 0.0], "name": "far" }),
            "2e12",
        ),
    ] {
        let (path, loaded) = triangle_with("huge_transform", fields);
        let error = loaded.expect_err("the transform is too large");
        assert_eq!(
            error.to_string(),
            format!(
                "{}: node 0 \"far\": its world transform has an entry of {value}, beyond ±1e12 \
                 (the largest coordinate a scene may have)",
                path.display()
            )
        );
    }
    // JSON has no infinity, but 1e400 overflows f64.
    let (_, loaded) = triangle_with(
        "overflowing_transform",
        json!({ "translation": [1e300, 0.0, 0.0] }),
    );
    assert!(
        matches!(loaded, Err(SceneError::InvalidNode { .. })),
        "{loaded:?}"
    );
}

#[test]
fn vertices_beyond_the_largest_coordinate_are_an_error() {
    let mut gltf = Gltf::default();
    let positions = gltf.floats(&[[0.0, 0.0, 0.0], [1e30, 0.0, 0.0], [0.0, 1.0, 0.0]]);
    gltf.mesh("spike", json!({ "attributes": { "POSITION": positions } }));
    let path = temp_dir("huge_vertex").join("scene.gltf");
    gltf.write_embedded(&path);
    let error = Scene::from_gltf(&path).expect_err("the vertex is too far");
    assert!(
        error.to_string().starts_with(&format!(
            "{}: the geometry reaches 1.0000000150474662e30, beyond ±1e12",
            path.display()
        )),
        "{error}"
    );
}

#[test]
fn camera_planes_beyond_f32_are_errors_naming_the_camera() {
    for (perspective, field) in [
        (json!({ "yfov": 0.8, "znear": 1e39 }), "znear"),
        (json!({ "yfov": 0.8, "znear": 0.1, "zfar": 1e39 }), "zfar"),
    ] {
        let mut gltf = Gltf::default();
        gltf.triangle(None);
        let camera = gltf.push(
            "cameras",
            json!({ "name": "eye", "type": "perspective", "perspective": perspective }),
        );
        gltf.root(json!({ "camera": camera, "translation": [0.0, 0.0, 3.0] }));
        let path = temp_dir("huge_camera").join("scene.gltf");
        gltf.write_embedded(&path);
        let error = Scene::from_gltf(&path).expect_err("the plane is beyond f32");
        assert_eq!(
            error.to_string(),
            format!(
                "{}: camera 0 \"eye\": {field} is beyond the largest f32 (3.4028235e38)",
                path.display()
            )
        );
    }
}

#[test]
fn light_values_beyond_f32_are_errors_naming_the_light() {
    let mut gltf = Gltf::default();
    gltf.triangle(None);
    gltf.json["extensionsUsed"] = json!(["KHR_lights_punctual"]);
    gltf.json["extensions"] = json!({ "KHR_lights_punctual": { "lights": [
        { "name": "sun", "type": "point", "intensity": 1e39 }
    ] } });
    gltf.root(json!({ "extensions": { "KHR_lights_punctual": { "light": 0 } } }));
    let path = temp_dir("huge_light").join("scene.gltf");
    gltf.write_embedded(&path);
    let error = Scene::from_gltf(&path).expect_err("the intensity is beyond f32");
    assert_eq!(
        error.to_string(),
        format!(
            "{}: light 0 \"sun\": intensity is beyond the largest f32 (3.4028235e38)",
            path.display()
        )
    );
}

#[test]
fn the_range_of_the_brightest_light_without_range_is_finite() {
    // intensity * max(color) / cutoff overflowed f32 from about 3.4e36: an infinite light
    // volume, and a black frame.
    for intensity in [3.4e36, 1e37, f32::MAX] {
        let light = Light::point("bright", Default::default(), [1.0; 3], intensity, None);
        assert_eq!(light.kind, LightKind::Point);
        let range = light.effective_range(DEFAULT_CUTOFF_ILLUMINANCE).unwrap();
        let expected = (f64::from(intensity) / f64::from(DEFAULT_CUTOFF_ILLUMINANCE)).sqrt();
        assert!(range.is_finite(), "intensity {intensity:e}: range {range}");
        assert!(
            (f64::from(range) - expected).abs() <= expected * 1e-6,
            "intensity {intensity:e}: range {range:e}, expected {expected:e}"
        );
    }
    let light = Light::point("bright", Default::default(), [1.0; 3], f32::MAX, None);
    assert_eq!(light.effective_range(1e-45), Some(f32::MAX));
}

#[test]
fn a_missing_image_names_the_gltf_file_the_image_and_the_material() {
    let mut gltf = Gltf::default();
    gltf.push("images", json!({ "uri": "missing.png" }));
    gltf.push("textures", json!({ "source": 0 }));
    let material = gltf.push(
        "materials",
        json!({ "name": "painted", "pbrMetallicRoughness": { "baseColorTexture": { "index": 0 } } }),
    );
    gltf.triangle(Some(material));
    let dir = temp_dir("missing_image");
    let path = dir.join("scene.gltf");
    gltf.write_embedded(&path);
    let error = Scene::from_gltf(&path).expect_err("the image is missing");
    let folder = dir.canonicalize().unwrap();
    assert_eq!(
        error.to_string(),
        format!(
            "{}: image 0 \"missing.png\" (base color of material 0 \"painted\"): cannot read \
             {}: No such file or directory (os error 2)",
            path.display(),
            folder.join("missing.png").display()
        )
    );
}

#[test]
fn an_image_uri_outside_the_folder_names_the_image_and_the_material() {
    let mut gltf = Gltf::default();
    gltf.push("images", json!({ "uri": "/etc/hostname" }));
    gltf.push("textures", json!({ "source": 0 }));
    let material = gltf.push(
        "materials",
        json!({ "name": "painted", "pbrMetallicRoughness": { "baseColorTexture": { "index": 0 } } }),
    );
    gltf.triangle(Some(material));
    let path = temp_dir("outside_image").join("scene.gltf");
    gltf.write_embedded(&path);
    let error = Scene::from_gltf(&path).expect_err("the image is outside");
    assert!(
        matches!(error, SceneError::InvalidImage { .. }),
        "{error:?}"
    );
    assert!(
        error.to_string().contains(
            "image 0 \"/etc/hostname\" (base color of material 0 \"painted\"): URI \
             `/etc/hostname` points to /etc/hostname, outside the asset folder"
        ),
        "{error}"
    );
}

#[test]
fn a_mesh_placed_by_many_nodes_counts_its_geometry_once_per_handedness() {
    use rgraph_scene::{AssetPolicy, Mesh, DEFAULT_MAX_SCENE_BYTES};
    use std::sync::Arc;
    assert_eq!(DEFAULT_MAX_SCENE_BYTES, 4 << 30);
    let mut gltf = Gltf::default();
    let mesh = gltf.triangle(None);
    // One triangle without normals: 3 vertices of 56 bytes and 3 indices of 4, 180 bytes,
    // which the unmirrored placements share, and the mirrored ones a reversed copy; ten
    // more nodes place it again, one of them mirrored.
    for _ in 0..9 {
        gltf.root(json!({ "mesh": mesh }));
    }
    gltf.root(json!({ "mesh": mesh, "scale": [-1, 1, 1] }));
    let path = temp_dir("geometry_limit").join("scene.gltf");
    gltf.write_embedded(&path);
    let policy = |max_scene_bytes| AssetPolicy {
        max_scene_bytes,
        ..AssetPolicy::default()
    };
    let record = std::mem::size_of::<Mesh>();
    let needed = 2 * 180 + 11 * record as u64;
    let scene = Scene::from_gltf_with(&path, &policy(needed)).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene.meshes.len(), 11);
    let (first, mirrored) = (&scene.meshes[0], &scene.meshes[10]);
    assert!(scene.meshes[1..10]
        .iter()
        .all(|m| Arc::ptr_eq(&m.vertices, &first.vertices)
            && Arc::ptr_eq(&m.indices, &first.indices)));
    assert!(!Arc::ptr_eq(&mirrored.indices, &first.indices));
    assert_eq!(*mirrored.indices, [0, 2, 1]);
    let error = Scene::from_gltf_with(&path, &policy(needed - 1)).expect_err("one byte short");
    assert_eq!(
        error.to_string(),
        format!(
            "{}: mesh 0 \"triangle\": placing it 11 times (360 bytes of geometry, which its \
             undeformed placements share, and {record} bytes a primitive placed) would take \
             the scene past {} bytes of vertices, indices and textures (the scene memory \
             limit)",
            path.display(),
            needed - 1
        )
    );
}

#[test]
fn images_are_counted_against_the_scene_memory_limit_before_decoding() {
    use rgraph_scene::AssetPolicy;
    // A 64x64 PNG: 64 * 64 * 4 bytes, and a third more for mips, 21,844 bytes.
    let mut png = Vec::new();
    image::RgbaImage::new(64, 64)
        .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
        .unwrap();
    let mut gltf = Gltf::default();
    gltf.textured_triangle(&png);
    let path = temp_dir("image_budget").join("scene.gltf");
    gltf.write_embedded(&path);
    let policy = AssetPolicy {
        max_scene_bytes: 20_000,
        ..AssetPolicy::default()
    };
    let error = Scene::from_gltf_with(&path, &policy).expect_err("the image is over the limit");
    assert_eq!(
        error.to_string(),
        format!(
            "{}: image 0 (base color of material 0 \"painted\"): decoding it (64x64) would take \
             the scene past 20000 bytes of vertices, indices and textures (the scene memory \
             limit)",
            path.display()
        )
    );
}

#[test]
fn a_light_placed_by_more_nodes_than_the_light_limit_is_an_error() {
    use rgraph_scene::MAX_LIGHTS;
    assert_eq!(MAX_LIGHTS, 65_536);
    let with_lights = |count: u32| {
        let mut gltf = Gltf::default();
        gltf.triangle(None);
        gltf.json["extensionsUsed"] = json!(["KHR_lights_punctual"]);
        gltf.json["extensions"] =
            json!({ "KHR_lights_punctual": { "lights": [{ "type": "point", "intensity": 1.0 }] } });
        for _ in 0..count {
            gltf.root(json!({ "extensions": { "KHR_lights_punctual": { "light": 0 } } }));
        }
        let path = temp_dir("light_limit").join("scene.gltf");
        gltf.write_embedded(&path);
        (path.clone(), Scene::from_gltf(&path))
    };
    let (path, loaded) = with_lights(MAX_LIGHTS);
    assert_eq!(
        loaded.unwrap_or_else(|e| panic!("{e}")).lights.len(),
        65_536
    );
    let (path2, loaded) = with_lights(MAX_LIGHTS + 1);
    assert_eq!(path, path2);
    assert_eq!(
        loaded.expect_err("one light too many").to_string(),
        format!(
            "{}: more than 65536 lights (the most a scene may have: each is drawn as its own \
             volume)",
            path.display()
        )
    );
}

/// A triangle with one material `{ "name": "paint", ...fields }`, loaded.
fn painted(test: &str, fields: Value) -> (std::path::PathBuf, Result<Scene, SceneError>) {
    let mut gltf = Gltf::default();
    let mut material = json!({ "name": "paint" });
    for (key, value) in fields.as_object().unwrap() {
        material[key] = value.clone();
    }
    let material = gltf.push("materials", material);
    gltf.triangle(Some(material));
    let path = temp_dir(test).join("scene.gltf");
    gltf.write_embedded(&path);
    let loaded = Scene::from_gltf(&path);
    (path, loaded)
}

#[test]
fn material_factors_beyond_f32_are_errors_naming_the_material() {
    for (fields, field) in [
        (
            json!({ "emissiveFactor": [1e39, 0.0, 0.0] }),
            "emissiveFactor [inf, 0.0, 0.0]",
        ),
        (
            json!({ "pbrMetallicRoughness": { "roughnessFactor": -1e39 } }),
            "roughnessFactor [-inf]",
        ),
        (
            json!({ "extensions": { "KHR_materials_emissive_strength": { "emissiveStrength": 1e39 } } }),
            "emissiveStrength [inf]",
        ),
    ] {
        let (path, loaded) = painted("material_beyond_f32", fields);
        assert_eq!(
            loaded.expect_err("the factor is infinite").to_string(),
            format!(
                "{}: material 0 \"paint\": {field} is beyond the largest f32 (3.4028235e38)",
                path.display()
            )
        );
    }
}

#[test]
fn material_factors_outside_gltf_s_ranges_are_clamped_with_a_warning() {
    let (path, loaded) = painted(
        "material_clamped",
        json!({
            "pbrMetallicRoughness": { "baseColorFactor": [2.0, 0.5, -1.0, 1.0], "metallicFactor": 3.0 },
            "alphaMode": "MASK", "alphaCutoff": -0.5,
        }),
    );
    let scene = loaded.unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let material = &scene.materials[0];
    assert_eq!(material.base_color_factor, [1.0, 0.5, 0.0, 1.0]);
    assert_eq!(material.metallic_factor, 1.0);
    assert_eq!(
        scene.warnings,
        [
            "material 0 \"paint\": baseColorFactor [2.0, 0.5, -1.0, 1.0] is not within 0..=1; \
             clamped to [1.0, 0.5, 0.0, 1.0]",
            "material 0 \"paint\": metallicFactor [3.0] is not within 0..=1; clamped to [1.0]",
            "material 0 \"paint\": alphaCutoff [-0.5] is not at least 0; clamped to [0.0]",
        ]
    );
}

/// Meshes are counted before any is built: 1,025 primitives placed by 1,024 nodes are
/// 1,049,600 meshes, past the 1,048,576 the renderers bind per-mesh data for.
#[test]
fn more_meshes_than_the_mesh_limit_is_an_error_before_building() {
    use rgraph_scene::MAX_MESHES;
    assert_eq!(MAX_MESHES, 1 << 20);
    let mut gltf = Gltf::default();
    let positions = gltf.floats(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
    let primitives: Vec<_> = (0..1025)
        .map(|_| json!({ "attributes": { "POSITION": positions } }))
        .collect();
    let mesh = gltf.push(
        "meshes",
        json!({ "name": "many", "primitives": primitives }),
    );
    for _ in 0..1024 {
        gltf.root(json!({ "mesh": mesh }));
    }
    let path = temp_dir("mesh_limit").join("scene.gltf");
    gltf.write_embedded(&path);
    let error = Scene::from_gltf(&path).expect_err("too many meshes");
    assert_eq!(
        error.to_string(),
        format!(
            "{}: 1049600 meshes (glTF primitives as placed by nodes), more than 1048576 (the \
             most a scene may have: each keeps 128 bytes of per-mesh data in one device \
             binding)",
            path.display()
        )
    );
}
