//! Extreme case 6 (issue 6), light volumes. Most of it is tests/deferred_volumes_gpu.rs:
//! the camera outside, inside, exactly on a sphere's and a cone's surface and at a cone's
//! apex; spot cones of 0.3°, 89.5° and 90°; a point light whose range is a twentieth of a
//! pixel; each bit-identical to the full-screen evaluation per sample. This adds the
//! other end of the radius:
//!
//! - Extreme: a point light and a spot light of range 1e6, 1e5 above a 200 x 200 floor (a
//!   volume a million times the scene; the camera deep inside it), intensity 1e10 so
//!   that the cutoff keeps the full range and the floor still gets about 1 lux.
//! - Expected: the volume (its back faces, as the camera is inside) shades exactly what
//!   the full-screen draw of the same light shades.
//! - Bound asserted: with every sample shaded (deferred_per_sample_4x) the resolved HDR is
//!   bit-identical with `volumes: true` and `volumes: false`, and the light reaches most
//!   of the floor.

use crate::deferred_support;

use deferred_support::scenes::Parts;
use deferred_support::{gpu, Render};
use rgraph_scene::glam::{DVec3, Vec3};
use rgraph_scene::{Camera, Light, LightKind, Projection, Scene};

const SIZE: (u32, u32) = (48, 48);

fn scene(kind: LightKind) -> Scene {
    let mut parts = Parts::new();
    let grey = parts.material("grey", [0.5, 0.5, 0.5], 0.5);
    let d = |x: f64, z: f64| DVec3::new(x, 0.0, z);
    parts.mesh(
        "floor",
        &[vec![
            d(-100.0, 100.0),
            d(100.0, 100.0),
            d(100.0, -100.0),
            d(-100.0, -100.0),
        ]],
        grey,
    );
    parts.cuboid(
        "box",
        DVec3::new(-5.0, 0.0, -5.0),
        DVec3::new(5.0, 10.0, 5.0),
        grey,
    );
    parts.lights.push(Light {
        name: "huge".into(),
        kind,
        color: [1.0, 1.0, 1.0],
        intensity: 1.0e10,
        position: DVec3::new(3.0e4, 1.0e5, 2.0e4),
        direction: Vec3::new(-0.3, -1.0, -0.2).normalize(),
        range: Some(1.0e6),
    });
    let camera = Camera::look_at(
        "above",
        DVec3::new(60.0, 80.0, 90.0),
        DVec3::ZERO,
        DVec3::Y,
        Projection::Perspective {
            yfov: 0.9,
            znear: 0.5,
            zfar: None,
        },
    );
    parts.scene("huge light", camera)
}

#[test]
fn a_light_of_range_1e6_matches_its_full_screen_evaluation() {
    let gpu = gpu();
    for kind in [
        LightKind::Point,
        LightKind::Spot {
            inner_cone: 0.3,
            outer_cone: 0.6,
        },
    ] {
        let resolved = |volumes: bool| {
            let mut render = Render::new("deferred_per_sample_4x.ron", "huge-light", SIZE)
                .with_scene(scene(kind))
                .export_resolved();
            if !volumes {
                render = render.full_screen_lights();
            }
            render.run(&gpu).hdr(&gpu, "resolved")
        };
        let (with, without) = (resolved(true), resolved(false));
        let differing = with
            .iter()
            .zip(&without)
            .filter(|(a, b)| a.map(f32::to_bits) != b.map(f32::to_bits))
            .count();
        let lit = with.iter().filter(|p| p[0] + p[1] + p[2] > 0.01).count();
        println!("{kind:?}: {lit} lit pixels, {differing} differ");
        assert!(lit > with.len() / 2, "{kind:?}: only {lit} pixels lit");
        assert_eq!(
            differing, 0,
            "{kind:?}: pixels differ between the volume and the full-screen light"
        );
    }
}
