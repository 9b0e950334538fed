//! The automatic camera of a file without one: a unit sphere written as glTF fills about
//! 85% of the image height (the shorter side of landscape images) at several aspect
//! ratios, seen from the front and above; a file's own camera is kept.

use crate::common::{temp_dir, Gltf};

use glam::{DVec3, DVec4};
use rgraph_scene::{DepthConvention, Scene};
use serde_json::json;

/// Where the sphere is: away from the origin, so framing must look at its center.
const CENTER: [f32; 3] = [2.0, -1.0, 3.0];

/// A unit sphere about [`CENTER`] (64 x 128 quads: its outline within 0.03% of a true
/// sphere's), with a perspective camera node at `camera` if given, written as
/// `test`/sphere.gltf; returns the loaded scene.
fn sphere_file(test: &str, camera: Option<[f32; 3]>) -> Scene {
    let (rings, segments) = (64u32, 128u32);
    let mut positions = Vec::new();
    for ring in 0..=rings {
        let polar = std::f32::consts::PI * ring as f32 / rings as f32;
        for segment in 0..=segments {
            let azimuth = std::f32::consts::TAU * segment as f32 / segments as f32;
            positions.push([
                CENTER[0] + polar.sin() * azimuth.cos(),
                CENTER[1] + polar.cos(),
                CENTER[2] - polar.sin() * azimuth.sin(),
            ]);
        }
    }
    let row = segments + 1;
    let indices: Vec<u32> = (0..rings)
        .flat_map(|ring| (0..segments).map(move |segment| ring * row + segment))
        .flat_map(|i| [i, i + row, i + row + 1, i, i + row + 1, i + 1])
        .collect();
    let mut gltf = Gltf::default();
    let positions = gltf.floats(&positions);
    let indices = gltf.indices_u32(&indices);
    gltf.mesh(
        "sphere",
        json!({ "attributes": { "POSITION": positions }, "indices": indices }),
    );
    if let Some(translation) = camera {
        let camera = gltf.push(
            "cameras",
            json!({ "name": "file camera", "type": "perspective",
                    "perspective": { "yfov": 0.7, "znear": 0.1 } }),
        );
        gltf.root(json!({ "camera": camera, "translation": translation }));
    }
    let path = temp_dir(test).join("sphere.gltf");
    gltf.write_embedded(&path);
    Scene::load(path.to_str().unwrap()).unwrap_or_else(|e| panic!("{e}"))
}

/// The sphere's vertices on the image of `aspect` (width / height), in normalized device
/// coordinates: (-1, -1) bottom left, (1, 1) top right.
fn projected(scene: &Scene, aspect: f64) -> Vec<DVec3> {
    let camera = &scene.camera;
    let clip = camera
        .projection_matrix(aspect as f32, DepthConvention::Standard)
        .as_dmat4()
        * camera.view_matrix();
    scene.meshes[0]
        .world_positions()
        .map(|p| {
            let c = clip * DVec4::from((p, 1.0));
            assert!(c.w > 0.0, "{p} is behind the camera");
            c.truncate() / c.w
        })
        .collect()
}

/// At 16:9, 4:3 and 1:1 the sphere's outline spans 85% ± 2% of the image height (the
/// shorter side), centred; its width in pixels is its height in pixels (a round outline).
#[test]
fn a_unit_sphere_fills_85_percent_of_the_shorter_side() {
    let scene = sphere_file("framing_sphere", None);
    assert_eq!(scene.camera.name, "default");
    for (width, height) in [(1280.0, 720.0), (1024.0, 768.0), (512.0, 512.0)] {
        let aspect = width / height;
        let points = projected(&scene, aspect);
        let min = points.iter().fold(DVec3::MAX, |a, p| a.min(*p));
        let max = points.iter().fold(DVec3::MIN, |a, p| a.max(*p));
        let fill = (max.y - min.y) / 2.0;
        assert!(
            (fill - 0.85).abs() <= 0.02,
            "{width}x{height}: the sphere spans {:.1}% of the height",
            100.0 * fill
        );
        let pixels = (
            (max.x - min.x) * width / 2.0,
            (max.y - min.y) * height / 2.0,
        );
        assert!(
            (pixels.0 - pixels.1).abs() <= 0.01 * pixels.1,
            "{width}x{height}: the outline is {pixels:?} pixels"
        );
        let middle = (max + min) / 2.0;
        assert!(
            middle.x.abs() < 2e-3 && middle.y.abs() < 2e-3,
            "{width}x{height}: the outline's middle is at {middle}"
        );
    }
}

/// The automatic camera looks at the sphere's center from the front (+Z), 15° above the
/// horizontal.
#[test]
fn the_automatic_camera_looks_from_the_front_and_above() {
    let scene = sphere_file("framing_direction", None);
    let center = DVec3::from(CENTER.map(f64::from));
    let from_center = (scene.camera.position - center).normalize();
    let elevation = from_center.y.asin().to_degrees();
    assert!((elevation - 15.0).abs() < 1e-6, "elevation {elevation}°");
    assert!(
        from_center.x.abs() < 1e-9 && from_center.z > 0.0,
        "{from_center}"
    );
    assert!(scene.camera.forward().abs_diff_eq(-from_center, 1e-9));
}

/// A file with a camera keeps it: not framed.
#[test]
fn a_file_s_own_camera_is_kept() {
    let scene = sphere_file("framing_file_camera", Some([0.5, 0.25, 9.0]));
    assert!(
        scene.camera.name.contains("file camera"),
        "{}",
        scene.camera.name
    );
    assert_eq!(scene.camera.position, DVec3::new(0.5, 0.25, 9.0));
}
