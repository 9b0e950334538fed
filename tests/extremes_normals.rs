//! Extreme case 4 (issue 6), normals, the GPU half (the encoding's angular error over a
//! dense sphere is bounded on the CPU: passes/tests/extremes_normals.rs).
//!
//! - Extreme: vertex normals of zero length (which ask for the face normal, see
//!   tests/face_normals.rs), denormal (1e-42), huge (3e38, whose squared
//!   length overflows f32) and pointing away from the camera on a front face, and a floor
//!   seen at grazing angles (out to 1000 units from a camera 0.5 above it: normal nearly
//!   perpendicular to the view).
//! - Expected: every sample of every float target finite; the huge normal keeps its
//!   direction (it used to be normalized through an overflowing dot product into zero,
//!   stored as +Z: the G-buffer now scales by the largest component first).
//! - Bounds asserted: 0 non-finite values in any sample of the lit HDR, normal and view
//!   depth targets and the resolved image, HDR within [0, 65504]; the huge +X normal
//!   stored as exactly the octahedral (1, 0) in every sample it covers.

use crate::deferred_support;

use deferred_support::scenes::Parts;
use deferred_support::{gpu, Render};
use rgraph_scene::glam::{DVec3, Vec3};
use rgraph_scene::{Camera, Light, LightKind, Projection, Scene};

const SIZE: (u32, u32) = (64, 48);

/// Quads facing the camera, each with one kind of odd vertex normal, above a long floor.
fn odd_normals() -> Scene {
    let mut parts = Parts::new();
    let grey = parts.material("grey", [0.6, 0.6, 0.6], 0.3);
    let d = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
    let normals: [[f32; 3]; 4] = [
        [0.0, 0.0, 0.0],
        [1e-42, 0.0, 1e-42],
        [3e38, 0.0, 0.0],
        [0.0, 0.0, -1.0],
    ];
    for (i, normal) in normals.iter().enumerate() {
        let x = -2.0 + 1.0 * i as f64;
        let quad = vec![
            d(x, 0.0, 0.0),
            d(x + 0.9, 0.0, 0.0),
            d(x + 0.9, 1.0, 0.0),
            d(x, 1.0, 0.0),
        ];
        let mesh = parts.mesh(&format!("normal {normal:?}"), &[quad], grey);
        for v in std::sync::Arc::make_mut(&mut parts.meshes[mesh].vertices) {
            v.normal = *normal;
        }
    }
    parts.mesh(
        "floor",
        &[vec![
            d(-50.0, -0.5, 4.0),
            d(50.0, -0.5, 4.0),
            d(50.0, -0.5, -1000.0),
            d(-50.0, -0.5, -1000.0),
        ]],
        grey,
    );
    parts.lights.push(Light::point(
        "point",
        d(0.0, 1.5, 2.0),
        [1.0; 3],
        20.0,
        None,
    ));
    parts.lights.push(Light {
        name: "sun".into(),
        kind: LightKind::Directional,
        color: [1.0, 1.0, 1.0],
        intensity: 2.0,
        position: DVec3::ZERO,
        direction: Vec3::new(0.2, -1.0, -0.5).normalize(),
        range: None,
    });
    let camera = Camera::look_at(
        "front",
        d(0.0, 0.0, 5.0),
        d(0.0, 0.0, 0.0),
        DVec3::Y,
        Projection::Perspective {
            yfov: 0.9,
            znear: 0.01,
            zfar: None,
        },
    );
    parts.scene("odd normals", camera)
}

#[test]
fn degenerate_normals_and_grazing_angles_render_finite() {
    let gpu = gpu();
    let scene = odd_normals();
    // Where the huge-normal quad (x 0..0.9, y 0..1 at z 0) is: project its center.
    let view_proj = scene.camera.projection.matrix(
        SIZE.0 as f32 / SIZE.1 as f32,
        rgraph_scene::DepthConvention::Standard,
    ) * scene.camera.view_matrix().as_mat4();
    let ndc = view_proj.project_point3(Vec3::new(0.45, 0.5, 0.0));
    let center = (
        ((ndc.x + 1.0) / 2.0 * SIZE.0 as f32) as u32,
        ((1.0 - ndc.y) / 2.0 * SIZE.1 as f32) as u32,
    );
    for pipeline in [
        "deferred_msaa_4x.ron",
        "deferred_per_sample_4x.ron",
        "deferred_noaa.ron",
    ] {
        let (hdr, resolved) = match pipeline {
            "deferred_noaa.ron" => ("hdr_lit", "hdr_lit"),
            _ => ("hdr_lit", "resolved"),
        };
        let export = if hdr == resolved {
            "outputs: [\"hdr_lit\", \"normal\", \"view_depth\", \"color\",".to_owned()
        } else {
            format!("outputs: [\"{hdr}\", \"normal\", \"view_depth\", \"{resolved}\", \"color\",")
        };
        let frame = Render::new(pipeline, "odd-normals", SIZE)
            .with_scene(scene.clone())
            .edit("outputs: [\"color\",", &export)
            .run(&gpu);
        let mut checked = 0;
        for target in [hdr, "normal", "view_depth", resolved] {
            let samples = frame.samples(&gpu, target);
            for (i, pixel) in samples.iter().enumerate() {
                for (s, texel) in pixel.iter().enumerate() {
                    let (x, y) = (i as u32 % SIZE.0, i as u32 / SIZE.0);
                    let hdr_range = target == hdr || target == resolved;
                    let ok = texel.iter().all(|c| c.is_finite())
                        && (!hdr_range || texel[..3].iter().all(|c| (0.0..=65504.0).contains(c)));
                    assert!(
                        ok,
                        "{pipeline}: {target} sample {s} of pixel ({x}, {y}) is {texel:?}"
                    );
                    checked += 1;
                }
            }
        }
        let normals = frame.samples(&gpu, "normal");
        let at_center = &normals[(center.1 * SIZE.0 + center.0) as usize];
        for (s, n) in at_center.iter().enumerate() {
            assert_eq!(
                n[..2],
                [1.0, 0.0],
                "{pipeline}: sample {s} of pixel {center:?} (the quad with normal 3e38 along \
                 +X) stores the octahedral {:?}, not +X's (1, 0)",
                &n[..2]
            );
        }
        // The lit floor reaches the horizon: grazing samples were shaded, not dropped.
        let lit = frame
            .samples(&gpu, resolved)
            .iter()
            .filter(|p| p[0][0] + p[0][1] + p[0][2] > 0.0)
            .count();
        assert!(
            lit > (SIZE.0 * SIZE.1 / 3) as usize,
            "{pipeline}: only {lit} lit pixels"
        );
        println!("{pipeline}: {checked} texels finite, {lit} lit pixels");
    }
}
