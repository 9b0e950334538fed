//! The scene model's math: projections (standard and reversed-Z, finite and infinite), view
//! transforms, light ranges and volumes, bounds, flat normals and statistics.

use glam::{DVec3, Mat4, Vec3, Vec4};
use rgraph_scene::{
    flat_shaded, Aabb, BoundingSphere, Camera, DepthConvention, Light, LightKind, LightVolume,
    Projection, Scene, Vertex, DEFAULT_CUTOFF_ILLUMINANCE,
};

/// Depth of the view-space point (0, 0, -distance).
fn depth(projection: Mat4, distance: f32) -> f32 {
    let clip = projection * Vec4::new(0.0, 0.0, -distance, 1.0);
    clip.z / clip.w
}

#[test]
fn perspective_depth_conventions() {
    let finite = Projection::Perspective {
        yfov: 1.0,
        znear: 0.5,
        zfar: Some(100.0),
    };
    let standard = finite.matrix(1.5, DepthConvention::Standard);
    let reversed = finite.matrix(1.5, DepthConvention::ReversedZ);
    assert!((depth(standard, 0.5)).abs() < 1e-6 && (depth(standard, 100.0) - 1.0).abs() < 1e-6);
    assert!((depth(reversed, 0.5) - 1.0).abs() < 1e-6 && depth(reversed, 100.0).abs() < 1e-6);

    let infinite = Projection::Perspective {
        yfov: 1.0,
        znear: 0.5,
        zfar: None,
    };
    let standard = infinite.matrix(1.5, DepthConvention::Standard);
    let reversed = infinite.matrix(1.5, DepthConvention::ReversedZ);
    assert!(depth(standard, 0.5).abs() < 1e-6 && depth(standard, 1e7) > 0.99999);
    assert!((depth(reversed, 0.5) - 1.0).abs() < 1e-6 && depth(reversed, 1e7) < 1e-6);

    // The vertical field of view: a point at angle yfov/2 above the axis lands on NDC y = 1,
    // and the aspect ratio scales x.
    let clip = standard * Vec4::new(1.5 * (0.5f32).tan(), (0.5f32).tan(), -1.0, 1.0);
    assert!((clip.x / clip.w - 1.0).abs() < 1e-6 && (clip.y / clip.w - 1.0).abs() < 1e-6);
}

#[test]
fn orthographic_keeps_ymag_and_square_pixels() {
    let ortho = Projection::Orthographic {
        xmag: 3.0,
        ymag: 2.0,
        znear: 1.0,
        zfar: 11.0,
    };
    for (aspect, depth_convention, near_depth) in [
        (1.5, DepthConvention::Standard, 0.0),
        (2.0, DepthConvention::ReversedZ, 1.0),
    ] {
        let m = ortho.matrix(aspect, depth_convention);
        let corner = m * Vec4::new(2.0 * aspect, 2.0, -1.0, 1.0);
        assert!(
            corner.abs_diff_eq(Vec4::new(1.0, 1.0, near_depth, 1.0), 1e-6),
            "{corner}"
        );
        assert!((depth(m, 11.0) - (1.0 - near_depth)).abs() < 1e-6);
    }
}

#[test]
fn look_at_view_matrix_and_camera_relative_rotation_agree() {
    let eye = DVec3::new(1e6 + 0.25, 3.0, -2e6);
    let target = eye + DVec3::new(-4.0, -1.0, 2.0);
    let projection = Projection::Perspective {
        yfov: 1.0,
        znear: 0.1,
        zfar: None,
    };
    let camera = Camera::look_at("far away", eye, target, DVec3::Y, projection);
    let view = camera.view_matrix();
    assert!(view.transform_point3(eye).abs_diff_eq(DVec3::ZERO, 1e-6));
    let ahead = view.transform_point3(target);
    assert!(
        ahead.x.abs() < 1e-6 && ahead.y.abs() < 1e-6 && ahead.z < 0.0,
        "{ahead}"
    );
    assert!(camera
        .forward()
        .abs_diff_eq((target - eye).normalize(), 1e-12));
    // Camera-relative: subtract the position in f64, then rotate in f32.
    let p = eye + DVec3::new(0.5, 0.25, -3.0);
    let relative = camera
        .view_rotation()
        .transform_point3((p - camera.position).as_vec3());
    assert!(relative
        .as_dvec3()
        .abs_diff_eq(view.transform_point3(p), 1e-5));
}

fn light(kind: LightKind, range: Option<f32>) -> Light {
    Light {
        name: "test".into(),
        kind,
        color: [1.0, 0.5, 0.25],
        intensity: 100.0,
        position: DVec3::new(1.0, 2.0, 3.0),
        direction: Vec3::NEG_Y,
        range,
    }
}

#[test]
fn effective_range_is_the_cutoff_radius_or_the_gltf_range() {
    // sqrt(100 * max(color) / 0.01) = 100.
    assert_eq!(
        light(LightKind::Point, None).effective_range(0.01),
        Some(100.0)
    );
    assert_eq!(
        light(LightKind::Point, Some(12.5)).effective_range(0.01),
        Some(12.5)
    );
    assert_eq!(
        light(LightKind::Point, Some(500.0)).effective_range(0.01),
        Some(100.0)
    );
    assert_eq!(
        light(LightKind::Directional, None).effective_range(0.01),
        None
    );
    assert_eq!(
        light(LightKind::Point, None).effective_range(DEFAULT_CUTOFF_ILLUMINANCE),
        Some(100.0)
    );
    let dark = Light {
        intensity: 0.0,
        ..light(LightKind::Point, None)
    };
    assert_eq!(dark.effective_range(0.01), Some(0.0));
}

/// Points of the spot light's lit region: apex, cap and rim directions at full range.
fn sector_samples(l: &Light, range: f64, outer: f64) -> Vec<DVec3> {
    let axis = l.direction.as_dvec3();
    let (u, v) = axis.any_orthonormal_pair();
    let mut points = vec![l.position];
    for i in 0..=16 {
        let angle = outer * f64::from(i) / 16.0;
        for k in 0..8 {
            let around = std::f64::consts::TAU * f64::from(k) / 8.0;
            let dir = axis * angle.cos() + (u * around.cos() + v * around.sin()) * angle.sin();
            points.push(l.position + dir * range);
        }
    }
    points
}

#[test]
fn spot_bounding_spheres_contain_the_sector_for_narrow_and_wide_cones() {
    for (outer, expected_offset, expected_radius) in [
        (
            0.5f32,
            10.0 / (2.0 * 0.5f64.cos()),
            10.0 / (2.0 * 0.5f64.cos()),
        ),
        (1.2f32, 10.0 * 1.2f64.cos(), 10.0 * 1.2f64.sin()),
    ] {
        let spot = light(
            LightKind::Spot {
                inner_cone: 0.1,
                outer_cone: outer,
            },
            Some(10.0),
        );
        let BoundingSphere { center, radius } = spot.bounding_sphere(0.01).unwrap();
        assert!((radius - expected_radius).abs() < 1e-5, "{outer}: {radius}");
        assert!(center.abs_diff_eq(spot.position + DVec3::NEG_Y * expected_offset, 1e-5));
        for p in sector_samples(&spot, 10.0, f64::from(outer)) {
            assert!(p.distance(center) <= radius + 1e-5, "{outer}: {p} outside");
        }
    }
    assert_eq!(
        light(LightKind::Directional, None).bounding_sphere(0.01),
        None
    );
}

#[test]
fn light_volumes_by_kind() {
    let point = light(LightKind::Point, Some(12.5));
    assert_eq!(
        point.volume(0.01),
        LightVolume::Sphere(BoundingSphere {
            center: point.position,
            radius: 12.5
        })
    );
    let spot = light(
        LightKind::Spot {
            inner_cone: 0.2,
            outer_cone: 0.4,
        },
        Some(10.0),
    );
    let LightVolume::Cone {
        apex,
        axis,
        height,
        base_radius,
    } = spot.volume(0.01)
    else {
        panic!("spot lights get a cone")
    };
    assert_eq!((apex, axis, height), (spot.position, Vec3::NEG_Y, 10.0));
    assert!((base_radius - 10.0 * 0.4f32.tan()).abs() < 1e-6);
    assert_eq!(
        light(LightKind::Directional, None).volume(0.01),
        LightVolume::FullScreen
    );
}

#[test]
fn spots_wider_than_45_degrees_get_their_bounding_sphere_not_a_cone() {
    // At 90° the cone's base radius, 10 * tan(pi/2) in f32, would be about 2e8.
    for outer in [0.8f32, 1.2, std::f32::consts::FRAC_PI_2] {
        let spot = light(
            LightKind::Spot {
                inner_cone: 0.1,
                outer_cone: outer,
            },
            Some(10.0),
        );
        let LightVolume::Sphere(sphere) = spot.volume(0.01) else {
            panic!("{outer}: a wide spot gets a sphere");
        };
        assert_eq!(Some(sphere), spot.bounding_sphere(0.01), "{outer}");
        assert!(sphere.radius <= 10.0 + 1e-9, "{outer}: {}", sphere.radius);
    }
}

#[test]
fn aabb_union_and_sphere() {
    let a = Aabb::from_points([DVec3::new(1.0, 2.0, 3.0), DVec3::new(-1.0, 0.0, 5.0)]).unwrap();
    assert_eq!(
        (a.min, a.max),
        (DVec3::new(-1.0, 0.0, 3.0), DVec3::new(1.0, 2.0, 5.0))
    );
    let b = Aabb {
        min: DVec3::splat(4.0),
        max: DVec3::splat(6.0),
    };
    let u = a.union(&b);
    assert_eq!(
        (u.min, u.max),
        (DVec3::new(-1.0, 0.0, 3.0), DVec3::splat(6.0))
    );
    // Centred at (1, 2, 2), the farthest of the points is (0, 0, 0), 3 away.
    let points = [
        DVec3::ZERO,
        DVec3::new(2.0, 4.0, 2.0),
        DVec3::new(1.0, 2.0, 4.0),
    ];
    let sphere = BoundingSphere::around(DVec3::new(1.0, 2.0, 2.0), points);
    assert_eq!(
        sphere,
        BoundingSphere {
            center: DVec3::new(1.0, 2.0, 2.0),
            radius: 3.0
        }
    );
    assert_eq!(BoundingSphere::around(DVec3::ONE, []).radius, 0.0);
    assert_eq!(Aabb::from_points([]), None);
}

#[test]
fn flat_shading_unindexes_with_face_normals() {
    let positions = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
    ];
    let uvs = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.5, 0.5]];
    let indexed: Vec<Vertex> = positions
        .iter()
        .zip(uvs)
        .zip(0u16..)
        .map(|((&position, uv), i)| Vertex {
            position,
            normal: [9.0; 3],
            uv,
            color: [i; 4],
            tangent: Vertex::NO_TANGENT,
            uv1: [0.0; 2],
        })
        .collect();
    // A triangle facing +Z, one facing -Y, one degenerate.
    let (vertices, indices) = flat_shaded(&indexed, &[0, 1, 2, 0, 1, 3, 0, 0, 1]);
    assert_eq!(indices, (0..9).collect::<Vec<u32>>());
    let normals: Vec<[f32; 3]> = vertices.iter().map(|v| v.normal).collect();
    assert_eq!(&normals[0..3], &[[0.0, 0.0, 1.0]; 3]);
    assert_eq!(&normals[3..6], &[[0.0, -1.0, 0.0]; 3]);
    assert_eq!(
        &normals[6..9],
        &[[0.0, 0.0, 1.0]; 3],
        "degenerate triangles get a fixed normal"
    );
    assert_eq!(vertices[5].position, [0.0, 0.0, 1.0]);
    assert_eq!(vertices[5].uv, [0.5, 0.5]);
    assert_eq!(
        vertices[5].color, [3; 4],
        "attributes other than the normal are kept"
    );
}

#[test]
fn stats_count_by_feature_and_print_on_one_line() {
    let stats = Scene::load("builtin:unlit").unwrap().stats();
    assert_eq!(
        stats.to_string(),
        "4 meshes, 6 triangles, 14 vertices; lights: 0 point, 0 spot, 0 directional; \
         4 materials (4 unlit, 0 emissive, 0 mask, 0 blend, 0 textured, 4 double-sided), 0 textures"
    );
}
