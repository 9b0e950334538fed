//! Extreme case 2 (issue 6), world coordinates far from the origin. The base case is
//! tests/deferred_lit.rs (`a_scene_far_from_the_origin_renders_as_at_the_origin`:
//! builtin:spheres moved by (3e6, 1e6, -2e6), resolved HDR within 1e-3, bit-identical on
//! lavapipe); this extends it.
//!
//! - Extremes: builtin:dense (point and spot lights, many edges) moved by 1e6 and by 1e8
//!   along every axis (where f32 steps are 0.0625 and 8 units, larger than the scene's
//!   details), through the deferred pipeline and the forward reference's pipeline.
//! - Expected: rendering is camera-relative (model matrices, light positions and volumes
//!   made relative to the camera in f64 before they become f32), so the 8-bit image
//!   equals the one at the origin.
//! - Bound asserted: every channel of every pixel within 1/255 (measured on lavapipe:
//!   identical, 0 of 3,072 pixels differ).

use crate::deferred_support;
use crate::deferred_support::measure;

use deferred_support::{gpu, Render};
use rgraph_scene::glam::DVec3;
use rgraph_scene::Scene;

const SIZE: (u32, u32) = (64, 48);

fn moved(scene: &Scene, offset: DVec3) -> Scene {
    let mut scene = scene.clone();
    for mesh in &mut scene.meshes {
        mesh.transform.w_axis.x += offset.x;
        mesh.transform.w_axis.y += offset.y;
        mesh.transform.w_axis.z += offset.z;
    }
    for light in &mut scene.lights {
        light.position += offset;
    }
    scene.camera.position += offset;
    scene.bounds.min += offset;
    scene.bounds.max += offset;
    scene
}

#[test]
fn dense_scene_at_1e6_and_1e8_renders_as_at_the_origin() {
    let gpu = gpu();
    let base = Scene::load("builtin:dense").expect("builtin:dense loads");
    for pipeline in ["deferred_msaa_4x.ron", "forward_msaa_4x.ron"] {
        let color = |scene: Scene| {
            Render::new(pipeline, "builtin:dense", SIZE)
                .with_scene(scene)
                .read(&gpu, &["color"])
                .remove(0)
        };
        let origin = color(base.clone());
        for distance in [1e6, 1e8] {
            let far = color(moved(&base, DVec3::new(distance, -distance, distance)));
            let d = measure::diff(&origin, &far, None);
            println!("{pipeline} at {distance:e}: {d}");
            assert!(
                d.max <= 1,
                "{pipeline}: builtin:dense moved by {distance:e} differs from the origin's \
                 image: {d}"
            );
        }
    }
}

/// A glTF scene whose every node (four boxes on a floor, a point and a spot light, the
/// camera) is translated by `offset`: the file a user far from the origin would load.
/// Returns the file's path and each node's translation as written.
fn far_gltf(dir: &std::path::Path, offset: DVec3) -> (std::path::PathBuf, Vec<DVec3>) {
    use rgraph_scene::{Camera, Projection};
    use serde_json::json;

    // A unit cube, four vertices per face so each face has its own normal.
    let mut positions: Vec<f32> = Vec::new();
    let mut normals: Vec<f32> = Vec::new();
    let mut indices: Vec<u16> = Vec::new();
    for axis in 0..3 {
        for sign in [-1.0f32, 1.0] {
            let mut normal = [0.0f32; 3];
            normal[axis] = sign;
            let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
            let base = (positions.len() / 3) as u16;
            for (a, b) in [(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)] {
                let mut p = [0.0f32; 3];
                p[axis] = 0.5 * sign;
                p[u] = a;
                p[v] = b * sign;
                positions.extend(p);
                normals.extend(normal);
            }
            indices.extend([0, 1, 2, 0, 2, 3].map(|i| base + i));
        }
    }
    let mut bin: Vec<u8> = Vec::new();
    bin.extend(positions.iter().flat_map(|v| v.to_le_bytes()));
    bin.extend(normals.iter().flat_map(|v| v.to_le_bytes()));
    bin.extend(indices.iter().flat_map(|v| v.to_le_bytes()));
    let vertex_bytes = positions.len() * 4;

    let camera = Camera::look_at(
        "view",
        DVec3::new(4.3, 3.1, 5.2),
        DVec3::new(0.0, 0.4, 0.0),
        DVec3::Y,
        Projection::Perspective {
            yfov: 0.8,
            znear: 0.1,
            zfar: None,
        },
    );
    let spot_rotation = rgraph_scene::glam::DQuat::from_rotation_x(-1.3);
    // (translation, rotation, scale, what the node carries).
    let nodes = [
        (
            DVec3::new(0.0, -0.05, 0.0),
            [0.0, 0.0, 0.0, 1.0],
            [8.0, 0.1, 8.0],
            json!({"mesh": 0}),
        ),
        (
            DVec3::new(0.3, 0.5, 0.2),
            [0.0, 0.3826834, 0.0, 0.9238795],
            [1.0; 3],
            json!({"mesh": 0}),
        ),
        (
            DVec3::new(1.7, 0.4, -1.1),
            [0.0, 0.0, 0.0, 1.0],
            [0.8; 3],
            json!({"mesh": 0}),
        ),
        (
            DVec3::new(-1.3, 0.6, 0.9),
            [0.0, 0.0, 0.0, 1.0],
            [0.6, 1.2, 0.6],
            json!({"mesh": 0}),
        ),
        (
            DVec3::new(-0.4, 0.25, -1.9),
            [0.0, 0.0, 0.0, 1.0],
            [0.5; 3],
            json!({"mesh": 0}),
        ),
        (
            DVec3::new(1.0, 3.0, 2.0),
            [0.0, 0.0, 0.0, 1.0],
            [1.0; 3],
            json!({"extensions": {"KHR_lights_punctual": {"light": 0}}}),
        ),
        (
            DVec3::new(-1.5, 2.5, -0.5),
            spot_rotation.to_array(),
            [1.0; 3],
            json!({"extensions": {"KHR_lights_punctual": {"light": 1}}}),
        ),
        (
            camera.position,
            camera.orientation.to_array(),
            [1.0; 3],
            json!({"camera": 0}),
        ),
    ];
    let translations: Vec<DVec3> = nodes.iter().map(|(t, ..)| *t + offset).collect();
    let nodes: Vec<_> = nodes
        .into_iter()
        .zip(&translations)
        .map(|((_, rotation, scale, mut node), translation)| {
            node["translation"] = json!(translation.to_array());
            node["rotation"] = json!(rotation);
            node["scale"] = json!(scale);
            node
        })
        .collect();
    let name = format!("far_{:e}", offset.x);
    std::fs::write(dir.join(format!("{name}.bin")), &bin).unwrap();
    let document = json!({
        "asset": {"version": "2.0"},
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [
            {"type": "point", "color": [1.0, 0.9, 0.8], "intensity": 40.0, "range": 20.0},
            {"type": "spot", "color": [0.6, 0.7, 1.0], "intensity": 30.0,
             "spot": {"innerConeAngle": 0.3, "outerConeAngle": 0.6}}
        ]}},
        "scene": 0,
        "scenes": [{"nodes": (0..nodes.len()).collect::<Vec<_>>()}],
        "nodes": nodes,
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}}],
        "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.5, 0.3, 1.0],
                        "metallicFactor": 0.0, "roughnessFactor": 0.5}}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1},
                                    "indices": 2, "material": 0}]}],
        "buffers": [{"byteLength": bin.len(),
                     "uri": format!("{name}.bin")}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": vertex_bytes},
            {"buffer": 0, "byteOffset": vertex_bytes, "byteLength": vertex_bytes},
            {"buffer": 0, "byteOffset": 2 * vertex_bytes, "byteLength": indices.len() * 2}
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": positions.len() / 3,
             "type": "VEC3", "min": [-0.5, -0.5, -0.5], "max": [0.5, 0.5, 0.5]},
            {"bufferView": 1, "componentType": 5126, "count": normals.len() / 3, "type": "VEC3"},
            {"bufferView": 2, "componentType": 5123, "count": indices.len(), "type": "SCALAR"}
        ]
    });
    let path = dir.join(format!("{name}.gltf"));
    std::fs::write(&path, serde_json::to_vec_pretty(&document).unwrap()).unwrap();
    (path, translations)
}

/// The glTF loader reads node transforms as f64 (the `gltf` crate's f32 would quantise a
/// node 1e6 away to 1/16 unit, 1e8 away to 8 units): each is loaded exactly as written, and
/// the image equals the one of the same file at the origin within 1/255.
#[test]
fn a_gltf_file_at_1e6_and_1e8_renders_as_at_the_origin() {
    let gpu = gpu();
    let dir = tempfile::tempdir().unwrap();
    let load = |offset: DVec3| {
        let (path, translations) = far_gltf(dir.path(), offset);
        let spec = path.to_str().unwrap().to_owned();
        let scene = Scene::load(&spec).unwrap_or_else(|e| panic!("{spec}: {e}"));
        // Nodes 0 to 4 carry the meshes, in order; 7 the camera.
        for (mesh, written) in scene.meshes.iter().zip(&translations) {
            assert_eq!(mesh.transform.w_axis.truncate(), *written, "{spec}");
        }
        assert_eq!(scene.camera.position, translations[7], "{spec}");
        scene
    };
    let color = |scene: Scene| {
        Render::new("deferred_msaa_4x.ron", "far.gltf", SIZE)
            .with_scene(scene)
            .read(&gpu, &["color"])
            .remove(0)
    };
    let render = |offset: DVec3| color(load(offset));
    let origin = render(DVec3::ZERO);
    // What this test guards against: node translations rounded to f32, as the `gltf` crate
    // reads them, move silhouettes at 1e6 by more than 1/255.
    let mut rounded = load(DVec3::splat(1e6));
    let to_f32 = |v: DVec3| v.as_vec3().as_dvec3();
    for mesh in &mut rounded.meshes {
        let t = to_f32(mesh.transform.w_axis.truncate());
        mesh.transform.w_axis = t.extend(1.0);
    }
    for light in &mut rounded.lights {
        light.position = to_f32(light.position);
    }
    rounded.camera.position = to_f32(rounded.camera.position);
    let exact = render(DVec3::splat(1e6));
    let d = measure::diff(&exact, &color(rounded), None);
    println!("glTF at 1e6, translations rounded to f32: {d}");
    assert!(d.max > 1, "rounding to f32 changes nothing here: {d}");

    let lit = origin.pixels.iter().filter(|p| p[..3] != [0, 0, 0]).count();
    assert!(
        lit > origin.pixels.len() / 2,
        "the scene is mostly dark: {lit} lit pixels"
    );
    for distance in [1e6, 1e8] {
        let far = render(DVec3::new(distance, -distance, distance));
        let d = measure::diff(&origin, &far, None);
        println!("glTF at {distance:e}: {d}");
        assert!(
            d.max <= 1,
            "the glTF scene moved by {distance:e} differs from the origin's image: {d}"
        );
    }
}
