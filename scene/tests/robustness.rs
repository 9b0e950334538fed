//! Systematically damaged files must give errors (or load), never panic: every number in the
//! JSON replaced by hostile values, every byte of the binary chunk overwritten, and the file
//! truncated at every length.

use crate::common;

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::Path;

use common::{temp_dir, Gltf};
use rgraph_scene::Scene;
use serde_json::{json, Value};

/// A small asset touching most of the loader: indices, normals, uvs, a sparse accessor, a
/// PNG base-color texture with sampler, a hierarchy, a camera and a spot light.
fn asset() -> Gltf {
    let mut gltf = Gltf::default();
    let positions = gltf.floats(&[
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [1.0, 1.0, 0.0],
    ]);
    let normals = gltf.floats(&[[0.0, 0.0, 1.0]; 4]);
    let uvs = gltf.floats(&[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]]);
    let indices = gltf.indices_u16(&[0, 1, 2, 2, 1, 3]);
    let index_view = gltf.view(&1u16.to_le_bytes());
    let value_view = gltf.view(
        &[2.0f32, 0.0, 0.0]
            .iter()
            .flat_map(|v| v.to_le_bytes())
            .collect::<Vec<_>>(),
    );
    gltf.json["accessors"][positions]["sparse"] = json!({
        "count": 1,
        "indices": { "bufferView": index_view, "componentType": 5123 },
        "values": { "bufferView": value_view },
    });
    let mut png = Vec::new();
    image::RgbaImage::from_raw(1, 1, vec![10, 20, 30, 255])
        .unwrap()
        .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
        .unwrap();
    let png_view = gltf.view(&png);
    gltf.push(
        "images",
        json!({ "bufferView": png_view, "mimeType": "image/png" }),
    );
    gltf.push("samplers", json!({ "magFilter": 9728, "wrapS": 33071 }));
    gltf.push("textures", json!({ "source": 0, "sampler": 0 }));
    gltf.push(
        "materials",
        json!({ "pbrMetallicRoughness": { "baseColorTexture": { "index": 0 } }, "alphaMode": "MASK", "alphaCutoff": 0.5 }),
    );
    let mesh = gltf.push(
        "meshes",
        json!({ "primitives": [{
            "attributes": { "POSITION": positions, "NORMAL": normals, "TEXCOORD_0": uvs },
            "indices": indices, "material": 0, "mode": 4,
        }] }),
    );
    gltf.json["extensionsUsed"] = json!(["KHR_lights_punctual"]);
    gltf.json["extensions"] = json!({ "KHR_lights_punctual": { "lights": [
        { "type": "spot", "intensity": 5, "range": 3, "spot": { "innerConeAngle": 0.1, "outerConeAngle": 0.4 } }
    ] } });
    gltf.push(
        "cameras",
        json!({ "type": "perspective", "perspective": { "yfov": 0.7, "znear": 0.1, "zfar": 50 } }),
    );
    let child = gltf.push(
        "nodes",
        json!({ "mesh": mesh, "translation": [1, 2, 3], "rotation": [0, 0, 0, 1] }),
    );
    gltf.root(json!({ "children": [child], "scale": [2, 2, 2], "camera": 0, "extensions": { "KHR_lights_punctual": { "light": 0 } } }));
    gltf
}

/// Loads `path`, turning a panic into a test failure that names `what`.
fn load_without_panic(path: &Path, what: &str) {
    let outcome = catch_unwind(AssertUnwindSafe(|| Scene::from_gltf(path).map(|_| ())));
    assert!(outcome.is_ok(), "loading panicked after {what}");
}

/// Every numeric leaf of `value`, as a JSON pointer.
fn number_pointers(value: &Value, pointer: String, out: &mut Vec<String>) {
    match value {
        Value::Number(_) => out.push(pointer),
        Value::Array(items) => {
            for (i, item) in items.iter().enumerate() {
                number_pointers(item, format!("{pointer}/{i}"), out);
            }
        }
        Value::Object(map) => {
            for (key, item) in map {
                number_pointers(item, format!("{pointer}/{key}"), out);
            }
        }
        _ => {}
    }
}

#[test]
fn intact_asset_loads() {
    let path = temp_dir("robust_intact").join("asset.glb");
    asset().write_glb(&path);
    let scene = Scene::from_gltf(&path).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene.meshes[0].vertices[1].position, [2.0, 0.0, 0.0]);
    assert_eq!(scene.textures[0].rgba8, [10, 20, 30, 255]);
}

#[test]
fn every_json_number_replaced_by_hostile_values() {
    let original = asset();
    let mut pointers = Vec::new();
    number_pointers(&original.json, String::new(), &mut pointers);
    let path = temp_dir("robust_json").join("asset.glb");
    for pointer in &pointers {
        for hostile in [
            json!(-1),
            json!(0),
            json!(1),
            json!(3),
            json!(5),
            json!(4_294_967_295u64),
            json!(1e30),
            json!(-0.5),
        ] {
            let mut gltf = Gltf {
                json: original.json.clone(),
                bin: original.bin.clone(),
            };
            *gltf.json.pointer_mut(pointer).unwrap() = hostile.clone();
            gltf.write_glb(&path);
            load_without_panic(&path, &format!("setting {pointer} to {hostile}"));
        }
    }
}

#[test]
fn every_binary_byte_overwritten() {
    let original = asset();
    let path = temp_dir("robust_bin").join("asset.glb");
    for at in 0..original.bin.len() {
        for byte in [0x00, 0xff, 0x7f] {
            let mut gltf = Gltf {
                json: original.json.clone(),
                bin: original.bin.clone(),
            };
            gltf.bin[at] = byte;
            gltf.write_glb(&path);
            load_without_panic(&path, &format!("byte {at} = {byte:#x}"));
        }
    }
}

#[test]
fn file_truncated_at_every_length() {
    let dir = temp_dir("robust_truncated");
    let whole = dir.join("whole.glb");
    asset().write_glb(&whole);
    let bytes = std::fs::read(&whole).unwrap();
    let path = dir.join("cut.glb");
    for length in 0..bytes.len() {
        std::fs::write(&path, &bytes[..length]).unwrap();
        load_without_panic(&path, &format!("truncating to {length} bytes"));
    }
}
