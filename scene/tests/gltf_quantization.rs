//! KHR_mesh_quantization: a mesh written with every integer encoding the extension allows
//! loads to what its float version loads to, within one quantization step.

use crate::common;

use common::{temp_dir, Gltf, BYTE, SHORT, UNSIGNED_BYTE, UNSIGNED_SHORT};
use glam::DVec3;
use rgraph_scene::{Mesh, Scene};
use serde_json::json;

const POSITIONS: [[f32; 3]; 4] = [
    [-0.8, 0.3, 1.7],
    [1.9, -0.6, 0.2],
    [0.4, 1.2, -1.1],
    [1.1, 0.9, 0.6],
];
/// The box the positions are quantized in: its low and high corners.
const LOW: [f64; 3] = [-1.0, -1.0, -2.0];
const HIGH: [f64; 3] = [2.0, 2.0, 2.0];
const UVS: [[f32; 2]; 4] = [[0.1, 0.9], [0.75, 0.2], [0.5, 0.5], [1.0, 0.0]];

fn normals() -> [[f32; 3]; 4] {
    [
        [0.3, 0.5, 0.8],
        [-0.6, 0.1, 0.2],
        [0.0, -1.0, 0.1],
        [0.7, 0.7, -0.2],
    ]
    .map(|n| glam::Vec3::from_array(n).normalize().to_array())
}

fn tangents() -> [[f32; 4]; 4] {
    [
        [1.0, 0.2, -0.3],
        [0.1, 0.9, 0.4],
        [-0.5, 0.5, 0.7],
        [0.2, -0.1, 1.0],
    ]
    .map(|t| glam::Vec3::from_array(t).normalize().extend(1.0).to_array())
    .map(|[x, y, z, w]| [x, y, z, if x < 0.0 { -w } else { w }])
}

/// The largest stored value of an integer component type, and whether it is signed.
fn range(component: u32) -> (f64, bool) {
    match component {
        BYTE => (127.0, true),
        UNSIGNED_BYTE => (255.0, false),
        SHORT => (32767.0, true),
        UNSIGNED_SHORT => (65535.0, false),
        other => panic!("not an integer component type: {other}"),
    }
}

/// Stored integers as `component`'s little-endian bytes, each element padded to a multiple
/// of 4 bytes as glTF requires of vertex attributes. Returns the bytes and the stride.
fn encode(component: u32, elements: &[Vec<f64>]) -> (Vec<u8>, usize) {
    let size = match component {
        BYTE | UNSIGNED_BYTE => 1,
        _ => 2,
    };
    let stride = (size * elements[0].len()).next_multiple_of(4);
    let mut bytes = Vec::new();
    for element in elements {
        let start = bytes.len();
        for &q in element {
            match component {
                BYTE => bytes.push(q as i8 as u8),
                UNSIGNED_BYTE => bytes.push(q as u8),
                SHORT => bytes.extend((q as i16).to_le_bytes()),
                _ => bytes.extend((q as u16).to_le_bytes()),
            }
        }
        bytes.resize(start + stride, 0);
    }
    (bytes, stride)
}

/// An accessor of the quantized `elements` (already integers) with its own strided view.
fn quantized_accessor(
    gltf: &mut Gltf,
    component: u32,
    normalized: bool,
    type_: &str,
    elements: &[Vec<f64>],
) -> usize {
    let (bytes, stride) = encode(component, elements);
    let view = gltf.view(&bytes);
    gltf.json["bufferViews"][view]["byteStride"] = json!(stride);
    let mut accessor = json!({
        "bufferView": view, "componentType": component, "count": elements.len(),
        "type": type_, "normalized": normalized,
    });
    if type_ == "VEC3" {
        accessor["min"] = json!([-70000, -70000, -70000]);
        accessor["max"] = json!([70000, 70000, 70000]);
    }
    gltf.push("accessors", accessor)
}

/// How one quantized variant stores each attribute.
struct Encoding {
    position: (u32, bool),
    /// NORMAL and TANGENT: always normalized.
    direction: u32,
    uv: (u32, bool),
}

/// Adds the quantized mesh under a node whose transform dequantizes POSITION, as encoders
/// do: stored `q` is `t * MAX` of the position's place `t` in the box (-1..1 signed, 0..1
/// unsigned), read back as `q / MAX` (normalized) or `q` (not), so the node scales by the
/// box's (half) size, divided by MAX when not normalized. Unnormalized UVs are stored as
/// `uv * MAX`, which a material's KHR_texture_transform would scale back.
fn add_quantized(gltf: &mut Gltf, encoding: &Encoding) {
    let (component, normalized) = encoding.position;
    let (max, signed) = range(component);
    let (base, span) = match signed {
        true => (
            DVec3::from(LOW).midpoint(DVec3::from(HIGH)),
            (DVec3::from(HIGH) - DVec3::from(LOW)) / 2.0,
        ),
        false => (DVec3::from(LOW), DVec3::from(HIGH) - DVec3::from(LOW)),
    };
    let quantize = |t: f64, max: f64| (t * max).round();
    let positions: Vec<Vec<f64>> = POSITIONS
        .iter()
        .map(|p| {
            let t = (DVec3::from(p.map(f64::from)) - base) / span;
            t.to_array().map(|t| quantize(t, max)).to_vec()
        })
        .collect();
    let positions = quantized_accessor(gltf, component, normalized, "VEC3", &positions);
    let (direction_max, _) = range(encoding.direction);
    let directions = |values: Vec<Vec<f32>>| -> Vec<Vec<f64>> {
        values
            .into_iter()
            .map(|v| {
                v.into_iter()
                    .map(|c| quantize(f64::from(c), direction_max))
                    .collect()
            })
            .collect()
    };
    let normals = directions(normals().iter().map(|n| n.to_vec()).collect());
    let normals = quantized_accessor(gltf, encoding.direction, true, "VEC3", &normals);
    let tangents = directions(tangents().iter().map(|t| t.to_vec()).collect());
    let tangents = quantized_accessor(gltf, encoding.direction, true, "VEC4", &tangents);
    let (uv_component, uv_normalized) = encoding.uv;
    let (uv_max, _) = range(uv_component);
    let uvs: Vec<Vec<f64>> = UVS
        .iter()
        .map(|uv| uv.map(|c| quantize(f64::from(c), uv_max)).to_vec())
        .collect();
    let uvs = quantized_accessor(gltf, uv_component, uv_normalized, "VEC2", &uvs);
    let indices = gltf.indices_u16(&[0, 1, 2, 2, 1, 3]);
    let mesh = gltf.push(
        "meshes",
        json!({ "primitives": [{ "attributes": {
            "POSITION": positions, "NORMAL": normals, "TANGENT": tangents, "TEXCOORD_0": uvs,
        }, "indices": indices }] }),
    );
    let scale = match normalized {
        true => span,
        false => span / max,
    };
    gltf.root(json!({
        "mesh": mesh, "translation": base.to_array(), "scale": scale.to_array(),
    }));
}

/// World-space positions of a loaded mesh.
fn world_positions(mesh: &Mesh) -> Vec<DVec3> {
    mesh.vertices
        .iter()
        .map(|v| {
            mesh.transform
                .transform_point3(DVec3::from(v.position.map(f64::from)))
        })
        .collect()
}

#[test]
fn quantized_attributes_load_as_their_float_version_within_a_step() {
    let encodings = [
        Encoding {
            position: (BYTE, false),
            direction: BYTE,
            uv: (UNSIGNED_BYTE, true),
        },
        Encoding {
            position: (BYTE, true),
            direction: SHORT,
            uv: (UNSIGNED_SHORT, true),
        },
        Encoding {
            position: (UNSIGNED_BYTE, false),
            direction: BYTE,
            uv: (BYTE, true),
        },
        Encoding {
            position: (UNSIGNED_BYTE, true),
            direction: SHORT,
            uv: (SHORT, true),
        },
        Encoding {
            position: (SHORT, false),
            direction: BYTE,
            uv: (UNSIGNED_BYTE, false),
        },
        Encoding {
            position: (SHORT, true),
            direction: SHORT,
            uv: (UNSIGNED_SHORT, false),
        },
        Encoding {
            position: (UNSIGNED_SHORT, false),
            direction: BYTE,
            uv: (BYTE, false),
        },
        Encoding {
            position: (UNSIGNED_SHORT, true),
            direction: SHORT,
            uv: (SHORT, false),
        },
    ];
    let mut gltf = Gltf::default();
    gltf.json["extensionsUsed"] = json!(["KHR_mesh_quantization"]);
    gltf.json["extensionsRequired"] = json!(["KHR_mesh_quantization"]);
    // The float version, placed as it is.
    let positions = gltf.floats(&POSITIONS);
    let normals = gltf.floats(&normals());
    let tangents = gltf.floats(&tangents());
    let uvs = gltf.floats(&UVS);
    let indices = gltf.indices_u16(&[0, 1, 2, 2, 1, 3]);
    gltf.mesh(
        "float",
        json!({ "attributes": {
            "POSITION": positions, "NORMAL": normals, "TANGENT": tangents, "TEXCOORD_0": uvs,
        }, "indices": indices }),
    );
    for encoding in &encodings {
        add_quantized(&mut gltf, encoding);
    }
    let path = temp_dir("quantized_attributes").join("scene.gltf");
    gltf.write_embedded(&path);
    let scene = Scene::from_gltf(&path).unwrap_or_else(|e| panic!("{e}"));
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    assert_eq!(scene.meshes.len(), 1 + encodings.len());
    let reference = &scene.meshes[0];
    let expected = world_positions(reference);
    for (encoding, mesh) in encodings.iter().zip(&scene.meshes[1..]) {
        let what = format!(
            "position {:?}, directions {}, uv {:?}",
            encoding.position, encoding.direction, encoding.uv
        );
        assert_eq!(mesh.indices, reference.indices, "{what}");
        // One step of the position's encoding, in world units, per axis.
        let (max, signed) = range(encoding.position.0);
        let extent = DVec3::from(HIGH) - DVec3::from(LOW);
        let step = extent / if signed { 2.0 * max } else { max };
        for (got, want) in world_positions(mesh).iter().zip(&expected) {
            let error = (*got - *want).abs();
            assert!(error.cmple(step).all(), "{what}: {got} vs {want}");
        }
        let (direction_max, _) = range(encoding.direction);
        let (uv_max, _) = range(encoding.uv.0);
        // Unnormalized UVs are the stored integers; KHR_texture_transform scales them back.
        let uv_scale = if encoding.uv.1 { 1.0 } else { uv_max as f32 };
        for (got, want) in mesh.vertices.iter().zip(reference.vertices.iter()) {
            for (g, w) in got.normal.iter().zip(want.normal) {
                assert!(((g - w).abs() as f64) <= 1.0 / direction_max, "{what}");
            }
            // Tangents are stored as 16-bit snorm: a step of the encoding, plus rounding.
            for (g, w) in got.tangent.iter().zip(want.tangent) {
                let units = f64::from((g - w).abs());
                assert!(units <= 32767.0 / direction_max + 1.0, "{what}");
            }
            for (g, w) in got.uv.iter().zip(want.uv) {
                assert!(
                    (((g / uv_scale) - w).abs() as f64) <= 1.0 / uv_max,
                    "{what}"
                );
            }
        }
        if !encoding.uv.1 {
            // The stored integers themselves, not a normalized reading of them.
            let stored = UVS[1].map(|c| (f64::from(c) * uv_max).round() as f32);
            assert_eq!(mesh.vertices[1].uv, stored, "{what}");
        }
    }
}
