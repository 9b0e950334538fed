//! The committed fixtures (see tests/fixtures/README.md): an embedded-buffer .gltf and an
//! external-buffer .gltf, with exact expected values.

use crate::common;

use glam::{DMat4, DQuat, DVec3, Vec3};
use rgraph_scene::{
    AlphaMode, BoundingSphere, Camera, LightKind, Projection, Scene, FRAMING_FILL, FRAMING_YFOV,
};

fn load(name: &str) -> Scene {
    let path = common::fixture(name);
    Scene::load(path.to_str().unwrap()).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn child_of_translated_scaled_parent_lands_at_exact_world_positions() {
    let scene = load("hierarchy_embedded.gltf");
    assert_eq!(scene.meshes.len(), 1);
    let mesh = &scene.meshes[0];
    // parent: T(10,0,0) S(2); child: T(0,5,0) R_z(90°), all exactly representable.
    let expected = DMat4::from_cols_array(&[
        0.0, 2.0, 0.0, 0.0, //
        -2.0, 0.0, 0.0, 0.0, //
        0.0, 0.0, 2.0, 0.0, //
        10.0, 10.0, 0.0, 1.0,
    ]);
    assert_eq!(mesh.transform, expected);
    let world: Vec<DVec3> = mesh.world_positions().collect();
    assert_eq!(
        world,
        [
            DVec3::new(10.0, 10.0, 0.0),
            DVec3::new(10.0, 12.0, 0.0),
            DVec3::new(8.0, 10.0, 0.0)
        ]
    );
    assert_eq!(scene.bounds.min, DVec3::new(8.0, 10.0, 0.0));
    assert_eq!(scene.bounds.max, DVec3::new(10.0, 12.0, 0.0));
    assert_eq!(mesh.name, "mesh 0 \"triangle\" primitive 0");
}

#[test]
fn missing_normals_ask_for_face_normals() {
    let scene = load("hierarchy_embedded.gltf");
    let mesh = &scene.meshes[0];
    assert_eq!(*mesh.indices, [0, 1, 2]);
    assert!(mesh.vertices.iter().all(|v| v.normal == [0.0; 3]));
    assert!(mesh.vertices.iter().all(|v| v.uv == [0.0, 0.0]));
    let world_normal = mesh.normal_matrix() * DVec3::Z;
    assert_eq!(world_normal.normalize(), DVec3::Z);
}

#[test]
fn material_factors_mask_emissive_strength_and_double_sided() {
    let scene = load("hierarchy_embedded.gltf");
    assert_eq!(scene.materials.len(), 1);
    let m = &scene.materials[scene.meshes[0].material];
    assert_eq!(m.name, "material 0 \"masked emitter\"");
    assert_eq!(m.base_color_factor, [1.0, 0.0, 0.0, 1.0]);
    assert_eq!(m.metallic_factor, 0.25);
    assert_eq!(m.roughness_factor, 0.75);
    assert_eq!(m.emissive_factor, [0.5, 0.25, 0.0]);
    assert_eq!(m.emissive_strength, 4.0);
    assert_eq!(m.emission(), [2.0, 1.0, 0.0]);
    assert_eq!(m.alpha_mode, AlphaMode::Mask { cutoff: 0.3 });
    assert!(m.double_sided);
    assert!(!m.unlit);
    assert_eq!(m.base_color_texture, None);
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
}

#[test]
fn scene_without_camera_gets_the_framing_camera() {
    let scene = load("hierarchy_embedded.gltf");
    let camera = &scene.camera;
    // Bounds (8,10,0)..(10,12,0): sphere center (9,11,0); the farthest vertex a corner, √2
    // away.
    let center = DVec3::new(9.0, 11.0, 0.0);
    let radius = 2f64.sqrt();
    let sphere = BoundingSphere::around(center, scene.meshes[0].world_positions());
    assert_eq!(sphere, BoundingSphere { center, radius });
    assert_eq!(*camera, Camera::framing(&sphere));
    // The outline's radius on the image plane, FRAMING_FILL of the half height.
    let s = FRAMING_FILL * (f64::from(FRAMING_YFOV) / 2.0).tan();
    let distance = radius * (1.0 + 1.0 / (s * s)).sqrt();
    // From the glTF front (+Z), 15° above, looking at the center.
    let expected_eye =
        center + DVec3::new(0.0, 15f64.to_radians().sin(), 15f64.to_radians().cos()) * distance;
    assert!(
        camera.position.abs_diff_eq(expected_eye, 1e-12),
        "{}",
        camera.position
    );
    let to_center = (center - camera.position).normalize();
    assert!(camera.forward().abs_diff_eq(to_center, 1e-12));
    let Projection::Perspective { yfov, znear, zfar } = camera.projection else {
        panic!("framing camera is perspective")
    };
    assert_eq!((yfov, zfar), (FRAMING_YFOV, None));
    assert!((f64::from(znear) - 0.5 * (distance - radius)).abs() < 1e-6);
}

#[test]
fn external_buffer_indices_normals_uvs_and_unlit() {
    let scene = load("external/lights_cameras.gltf");
    let mesh = &scene.meshes[0];
    assert_eq!(*mesh.indices, [0, 1, 2, 0, 2, 3]);
    assert_eq!(mesh.vertices[2].position, [1.0, 0.0, -1.0]);
    assert_eq!(mesh.vertices[2].normal, [0.0, 1.0, 0.0]);
    assert_eq!(mesh.vertices[2].uv, [1.0, 0.0]);
    let m = &scene.materials[mesh.material];
    assert!(m.unlit);
    assert_eq!(m.base_color_factor, [0.2, 0.4, 0.6, 1.0]);
    assert_eq!(m.alpha_mode, AlphaMode::Opaque);
    assert!(!m.double_sided);
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
}

#[test]
fn punctual_lights_of_all_three_types() {
    let scene = load("external/lights_cameras.gltf");
    let [bulb, torch, sun] = &scene.lights[..] else {
        panic!("expected 3 lights, got {:?}", scene.lights)
    };
    assert_eq!(bulb.name, "light 0 \"bulb\"");
    assert_eq!(bulb.kind, LightKind::Point);
    assert_eq!(bulb.color, [1.0, 0.5, 0.25]);
    assert_eq!(bulb.intensity, 40.0);
    assert_eq!(bulb.range, Some(12.5));
    assert_eq!(bulb.position, DVec3::new(1.0, 2.0, 3.0));

    assert_eq!(
        torch.kind,
        LightKind::Spot {
            inner_cone: 0.25,
            outer_cone: 0.5
        }
    );
    assert_eq!((torch.intensity, torch.range), (100.0, Some(20.0)));
    assert_eq!(torch.color, [1.0; 3], "glTF default color");
    assert_eq!(torch.position, DVec3::new(0.0, 4.0, 0.0));
    assert!(
        torch.direction.abs_diff_eq(Vec3::NEG_Y, 1e-6),
        "{}",
        torch.direction
    );

    assert_eq!(sun.kind, LightKind::Directional);
    assert_eq!((sun.intensity, sun.range), (3.0, None));
    assert_eq!(sun.color, [1.0, 1.0, 0.9]);
    assert!(
        sun.direction.abs_diff_eq(Vec3::NEG_X, 1e-6),
        "{}",
        sun.direction
    );
}

#[test]
fn first_camera_in_scene_order_is_used() {
    let scene = load("external/lights_cameras.gltf");
    let camera = &scene.camera;
    assert_eq!(camera.name, "camera 0 \"main\"");
    assert_eq!(camera.position, DVec3::new(0.0, 1.0, 5.0));
    assert_eq!(camera.orientation, DQuat::IDENTITY);
    assert_eq!(
        camera.projection,
        Projection::Perspective {
            yfov: 0.8,
            znear: 0.05,
            zfar: Some(100.0)
        }
    );
}
