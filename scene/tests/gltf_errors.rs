//! Bad input gives a `SceneError` that names the file and the object at fault, never a panic.

use crate::common;

use std::path::Path;

use common::{temp_dir, Gltf};
use rgraph_scene::{Scene, SceneError};
use serde_json::json;

/// Writes `gltf` (embedded buffer) in a fresh directory, loads it and returns the error.
fn load_error(test: &str, gltf: &Gltf) -> (SceneError, String) {
    let path = temp_dir(test).join("bad.gltf");
    gltf.write_embedded(&path);
    expect_error(&path)
}

fn expect_error(path: &Path) -> (SceneError, String) {
    let error = Scene::load(path.to_str().unwrap()).expect_err("loading must fail");
    let message = error.to_string();
    assert!(
        message.contains(&path.display().to_string()),
        "message does not name the file: {message}"
    );
    (error, message)
}

#[test]
fn missing_file() {
    let (error, _) = expect_error(&temp_dir("missing").join("nowhere.glb"));
    assert!(matches!(error, SceneError::Io { .. }), "{error:?}");
}

#[test]
fn corrupt_gltf_and_glb_name_the_path() {
    let dir = temp_dir("corrupt");
    let text = dir.join("garbage.gltf");
    std::fs::write(&text, "{ this is not json").unwrap();
    let (error, _) = expect_error(&text);
    assert!(matches!(error, SceneError::Gltf { .. }), "{error:?}");

    let glb = dir.join("truncated.glb");
    std::fs::write(&glb, b"glTF\x02\0\0\0\xff\0\0\0\x10\0\0\0JSON{}").unwrap();
    let (error, _) = expect_error(&glb);
    assert!(matches!(error, SceneError::Gltf { .. }), "{error:?}");
}

#[test]
fn unimplemented_required_extension_is_an_error_naming_it() {
    let mut gltf = Gltf::default();
    gltf.triangle(None);
    gltf.json["extensionsUsed"] = json!(["KHR_draco_mesh_compression"]);
    gltf.json["extensionsRequired"] = json!(["KHR_draco_mesh_compression"]);
    let (error, message) = load_error("required_extension", &gltf);
    assert!(
        matches!(error, SceneError::UnsupportedRequiredExtension { ref extension, .. } if extension == "KHR_draco_mesh_compression")
    );
    assert!(
        message.contains("requires glTF extension KHR_draco_mesh_compression"),
        "{message}"
    );
}

/// A mesh named `broken` whose primitive 1 has `positions` and `normals`.
fn two_primitive_mesh(positions: &[[f32; 3]], normals: &[[f32; 3]]) -> Gltf {
    let mut gltf = Gltf::default();
    let good = gltf.floats(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
    let positions = gltf.floats(positions);
    let normals = gltf.floats(normals);
    let mesh = gltf.push(
        "meshes",
        json!({ "name": "broken", "primitives": [
            { "attributes": { "POSITION": good } },
            { "attributes": { "POSITION": positions, "NORMAL": normals } },
        ] }),
    );
    gltf.root(json!({ "mesh": mesh }));
    gltf
}

#[test]
fn nan_position_names_mesh_primitive_and_first_bad_vertex() {
    let mut positions = [[0.0, 0.0, 0.0]; 6];
    positions[4] = [0.0, f32::NAN, 0.0];
    positions[5] = [f32::INFINITY, 0.0, 0.0];
    let gltf = two_primitive_mesh(&positions, &[[0.0, 0.0, 1.0]; 6]);
    let (error, message) = load_error("nan_position", &gltf);
    assert!(
        matches!(
            error,
            SceneError::NonFiniteVertex {
                primitive: 1,
                vertex: 4,
                attribute: "position",
                ..
            }
        ),
        "{error:?}"
    );
    assert!(
        message.contains("mesh 0 \"broken\" primitive 1: vertex 4 has a non-finite position"),
        "{message}"
    );
}

#[test]
fn infinite_normal_before_nan_position_is_reported_first() {
    let mut positions = [[0.0, 0.0, 0.0]; 6];
    positions[3] = [f32::NAN, 0.0, 0.0];
    let mut normals = [[0.0, 0.0, 1.0]; 6];
    normals[1] = [0.0, f32::NEG_INFINITY, 0.0];
    let (error, _) = load_error("inf_normal", &two_primitive_mesh(&positions, &normals));
    assert!(
        matches!(
            error,
            SceneError::NonFiniteVertex {
                vertex: 1,
                attribute: "normal",
                ..
            }
        ),
        "{error:?}"
    );
}

#[test]
fn scene_without_triangles_is_an_error() {
    let mut gltf = Gltf::default();
    gltf.root(json!({ "name": "empty node" }));
    let (error, message) = load_error("empty", &gltf);
    assert!(matches!(error, SceneError::EmptyScene { .. }), "{error:?}");
    assert!(
        message.ends_with("the scene contains no triangles, points or lines"),
        "{message}"
    );

    // A LINE_STRIP of one vertex has no segment: nothing is left to draw.
    let mut lone_vertex = Gltf::default();
    let positions = lone_vertex.floats(&[[0.0, 0.0, 0.0]]);
    lone_vertex.mesh(
        "line",
        json!({ "attributes": { "POSITION": positions }, "mode": 3 }),
    );
    let (error, _) = load_error("lone_vertex", &lone_vertex);
    assert!(matches!(error, SceneError::EmptyScene { .. }), "{error:?}");
}

/// LINES needs two indices per segment: an odd count is an error naming the file, mesh,
/// primitive and the accessor it was read from (the indices, or POSITION without them).
#[test]
fn odd_line_counts_name_the_accessor() {
    let mut indexed = Gltf::default();
    let positions = indexed.floats(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
    let indices = indexed.indices_u16(&[0, 1, 2]);
    indexed.mesh(
        "wires",
        json!({ "attributes": { "POSITION": positions }, "indices": indices, "mode": 1 }),
    );
    let (error, message) = load_error("odd_lines", &indexed);
    assert!(
        matches!(
            error,
            SceneError::InvalidAccessor {
                attribute: "indices",
                accessor: 1,
                ..
            }
        ),
        "{error:?}"
    );
    assert!(
        message.contains("odd_lines")
            && message.contains("mesh 0 \"wires\" primitive 0")
            && message.contains("LINES needs an even number of indices (two per segment), has 3"),
        "{message}"
    );

    let mut unindexed = Gltf::default();
    let positions = unindexed.floats(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
    unindexed.mesh(
        "wires",
        json!({ "attributes": { "POSITION": positions }, "mode": 1 }),
    );
    let (error, _) = load_error("odd_lines_unindexed", &unindexed);
    assert!(
        matches!(
            error,
            SceneError::InvalidAccessor {
                attribute: "POSITION",
                accessor: 0,
                ..
            }
        ),
        "{error:?}"
    );
}

/// A point or line index past the vertices is the error a triangle's is, naming the
/// file, mesh, primitive and index.
#[test]
fn point_index_out_of_range() {
    let mut gltf = Gltf::default();
    let positions = gltf.floats(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]]);
    let indices = gltf.indices_u16(&[0, 1, 2]);
    gltf.mesh(
        "dots",
        json!({ "attributes": { "POSITION": positions }, "indices": indices, "mode": 0 }),
    );
    let (error, message) = load_error("point_range", &gltf);
    assert!(
        matches!(
            error,
            SceneError::IndexOutOfRange {
                position: 2,
                index: 2,
                vertex_count: 2,
                ..
            }
        ),
        "{error:?}"
    );
    assert!(message.contains("mesh 0 \"dots\" primitive 0"), "{message}");
}

#[test]
fn index_out_of_range() {
    let mut gltf = Gltf::default();
    let positions = gltf.floats(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
    let indices = gltf.indices_u16(&[0, 1, 2, 2, 1, 3]);
    gltf.mesh(
        "overindexed",
        json!({ "attributes": { "POSITION": positions }, "indices": indices }),
    );
    let (error, message) = load_error("index_range", &gltf);
    assert!(
        matches!(
            error,
            SceneError::IndexOutOfRange {
                position: 5,
                index: 3,
                vertex_count: 3,
                ..
            }
        ),
        "{error:?}"
    );
    assert!(
        message.contains("mesh 0 \"overindexed\" primitive 0"),
        "{message}"
    );
}

#[test]
fn triangle_list_with_leftover_indices() {
    let mut gltf = Gltf::default();
    let positions = gltf.floats(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
    let indices = gltf.indices_u16(&[0, 1, 2, 0]);
    gltf.mesh(
        "ragged",
        json!({ "attributes": { "POSITION": positions }, "indices": indices }),
    );
    let (error, message) = load_error("ragged", &gltf);
    assert!(
        matches!(error, SceneError::InvalidPrimitive { .. }),
        "{error:?}"
    );
    assert!(message.contains("multiple of 3"), "{message}");
}

#[test]
fn accessor_past_its_buffer_view() {
    let mut gltf = Gltf::default();
    let positions = gltf.floats(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
    gltf.json["accessors"][positions]["count"] = json!(1000);
    gltf.mesh(
        "truncated",
        json!({ "attributes": { "POSITION": positions } }),
    );
    let (error, message) = load_error("overrun", &gltf);
    assert!(
        matches!(
            error,
            SceneError::InvalidAccessor {
                attribute: "POSITION",
                accessor: 0,
                ..
            }
        ),
        "{error:?}"
    );
    assert!(message.contains("overrun"), "{message}");
}

#[test]
fn huge_accessor_without_buffer_view_is_refused_not_allocated() {
    let mut gltf = Gltf::default();
    let index_view = gltf.view(&0u16.to_le_bytes());
    let value_view = gltf.view(&[0u8; 12]);
    let positions = gltf.push(
        "accessors",
        json!({
            "componentType": 5126, "count": 1_000_000_000u64, "type": "VEC3",
            "min": [0, 0, 0], "max": [0, 0, 0],
            "sparse": {
                "count": 1,
                "indices": { "bufferView": index_view, "componentType": 5123 },
                "values": { "bufferView": value_view },
            },
        }),
    );
    gltf.mesh(
        "phantom",
        json!({ "attributes": { "POSITION": positions } }),
    );
    // A billion vertices: refused from the accessor's count, before anything is read.
    let (error, message) = load_error("viewless", &gltf);
    assert!(matches!(error, SceneError::InvalidMesh { .. }), "{error:?}");
    assert!(
        message.ends_with(
            "mesh 0 \"phantom\": building it would take the scene past 4294967296 bytes of \
             vertices, indices and textures (the scene memory limit)"
        ),
        "{message}"
    );
}

#[test]
fn node_cycle() {
    let mut gltf = Gltf::default();
    gltf.triangle(None);
    gltf.root(json!({ "name": "a", "children": [2] }));
    gltf.push("nodes", json!({ "name": "b", "children": [1] }));
    let (error, message) = load_error("cycle", &gltf);
    assert!(
        matches!(error, SceneError::NodeHierarchy { .. }),
        "{error:?}"
    );
    assert!(message.contains("node 1 \"a\""), "{message}");
}

#[test]
fn missing_external_buffer_names_the_buffer_and_the_bin_file() {
    let mut gltf = Gltf::default();
    gltf.triangle(None);
    let dir = temp_dir("missing_bin");
    let path = dir.join("scene.gltf");
    gltf.write_external(&path, "present.bin", "absent.bin");
    let (error, message) = expect_error(&path);
    assert!(
        matches!(error, SceneError::InvalidBuffer { buffer: 0, .. }),
        "{error:?}"
    );
    assert!(
        message.starts_with(&format!(
            "{}: buffer 0: cannot read {}: ",
            path.display(),
            dir.join("absent.bin").display()
        )),
        "{message}"
    );
}

#[test]
fn remote_uri_is_refused() {
    let mut gltf = Gltf::default();
    gltf.triangle(None);
    let path = temp_dir("remote").join("scene.gltf");
    gltf.write_external(&path, "scene.bin", "https://example.com/scene.bin");
    let (error, message) = expect_error(&path);
    assert!(
        matches!(error, SceneError::InvalidBuffer { buffer: 0, .. }),
        "{error:?}"
    );
    assert!(
        message.contains("only relative paths and data URIs"),
        "{message}"
    );
}

#[test]
fn glb_without_its_binary_chunk() {
    let mut gltf = Gltf::default();
    gltf.triangle(None);
    gltf.bin.clear();
    gltf.json["buffers"] = json!([{ "byteLength": 36 }]);
    let path = temp_dir("glb_no_bin").join("scene.glb");
    gltf.write_glb(&path);
    let (error, _) = expect_error(&path);
    assert!(
        matches!(error, SceneError::InvalidBuffer { buffer: 0, .. }),
        "{error:?}"
    );
}

#[test]
fn spot_cone_wider_than_a_hemisphere() {
    let mut gltf = Gltf::default();
    gltf.triangle(None);
    gltf.json["extensionsUsed"] = json!(["KHR_lights_punctual"]);
    gltf.json["extensions"] = json!({ "KHR_lights_punctual": { "lights": [
        { "name": "floodlight", "type": "spot", "spot": { "innerConeAngle": 0.2, "outerConeAngle": 2.0 } }
    ] } });
    gltf.root(json!({ "extensions": { "KHR_lights_punctual": { "light": 0 } } }));
    let (error, message) = load_error("wide_spot", &gltf);
    assert!(
        matches!(error, SceneError::InvalidLight { .. }),
        "{error:?}"
    );
    assert!(message.contains("light 0 \"floodlight\""), "{message}");
}

#[test]
fn camera_type_without_its_projection_object() {
    let mut gltf = Gltf::default();
    gltf.triangle(None);
    let camera = gltf.push(
        "cameras",
        json!({ "name": "confused", "type": "perspective", "orthographic": { "xmag": 1, "ymag": 1, "znear": 0, "zfar": 1 } }),
    );
    gltf.root(json!({ "camera": camera }));
    let (error, message) = load_error("camera_mismatch", &gltf);
    assert!(
        matches!(error, SceneError::InvalidCamera { .. }),
        "{error:?}"
    );
    assert!(message.contains("camera 0 \"confused\""), "{message}");
}

#[test]
fn undecodable_base_color_image_names_image_and_material() {
    let mut gltf = Gltf::default();
    let view = gltf.view(b"definitely not a png");
    gltf.push(
        "images",
        json!({ "name": "noise", "bufferView": view, "mimeType": "image/png" }),
    );
    gltf.push("textures", json!({ "source": 0 }));
    let material = gltf.push(
        "materials",
        json!({ "name": "painted", "pbrMetallicRoughness": { "baseColorTexture": { "index": 0 } } }),
    );
    gltf.triangle(Some(material));
    let (error, message) = load_error("bad_image", &gltf);
    assert!(
        matches!(error, SceneError::InvalidImage { .. }),
        "{error:?}"
    );
    assert!(
        message.contains("image 0 \"noise\" (base color of material 0 \"painted\")"),
        "{message}"
    );
}

/// Found by tests/fuzz.rs: gltf 1.4 panicked on a GLB header declaring fewer bytes than
/// the header itself.
#[test]
fn a_glb_header_declaring_less_than_itself_is_an_error() {
    let path = temp_dir("glb_short_header").join("short.glb");
    let mut glb = b"glTF".to_vec();
    glb.extend_from_slice(&2u32.to_le_bytes());
    glb.extend_from_slice(&4u32.to_le_bytes());
    glb.extend_from_slice(b"\x10\0\0\0JSON{}      ");
    std::fs::write(&path, glb).unwrap();
    let (error, message) = expect_error(&path);
    assert!(matches!(error, SceneError::InvalidGlb { .. }), "{error:?}");
    assert!(
        message.ends_with(
            "not a valid GLB file: the header declares a length of 4 bytes, less than the \
             header's own 12"
        ),
        "{message}"
    );
}
