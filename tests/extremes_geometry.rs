//! Extreme case 5 (issue 6), geometry.
//!
//! - Extremes: zero-area triangles (three collinear corners, three equal corners);
//!   triangles far smaller than the sample spacing (0.02 pixels across), one around a
//!   pixel center (no sample inside) and one around one sample position; a triangle 1e6
//!   times larger than the view; a triangle with a corner behind the camera (clipped by
//!   the near plane); a mesh of 1,000,000 triangles rendered at 16x16.
//! - Expected: no crash and no device error; every sample of every float target finite;
//!   coverage decides: a triangle that covers no sample changes nothing, one that covers
//!   one sample of four changes that sample only and the resolved pixel by exactly a
//!   quarter of the difference; the huge triangle covers every sample it should.
//! - Bounds asserted: 0 non-finite values; the 0-sample triangle leaves the resolved image
//!   bit-identical; the 1-sample triangle changes 1 sample and its pixel by (fg - bg) / 4
//!   (within half-float rounding, 1e-3); the huge triangle leaves 0 background samples.
//!
//! NaN and Inf vertices are rejected when a glTF file loads, naming mesh, primitive and
//! vertex: scene/tests/gltf_errors.rs
//! (`nan_position_names_mesh_primitive_and_first_bad_vertex`,
//! `infinite_normal_before_nan_position_is_reported_first`), and damaged numbers never
//! panic the loader (scene/tests/robustness.rs).

use crate::deferred_support;

use deferred_support::scenes::Parts;
use deferred_support::{gpu, Render};
use rgraph_core::gpu::Gpu;
use rgraph_scene::glam::{DMat4, DQuat, DVec3};
use rgraph_scene::{Camera, Mesh, Projection, Scene, Vertex};

const N: u32 = 32;
const EXPORTS: &str =
    "outputs: [\"hdr_lit\", \"albedo\", \"normal\", \"view_depth\", \"resolved\", \"color\",";

/// An orthographic camera looking down -Z at x, y in [-1, 1]: pixel (px, py) of the N x N
/// image is world (px / 16 - 1, 1 - py / 16) for N = 32.
fn camera() -> Camera {
    Camera {
        name: "ortho".into(),
        position: DVec3::new(0.0, 0.0, 10.0),
        orientation: DQuat::IDENTITY,
        projection: Projection::Orthographic {
            xmag: 1.0,
            ymag: 1.0,
            znear: 0.1,
            zfar: 100.0,
        },
    }
}

fn world(px: f64, py: f64, z: f64) -> DVec3 {
    let scale = f64::from(N) / 2.0;
    DVec3::new(px / scale - 1.0, 1.0 - py / scale, z)
}

/// An unlit triangle (corners as given, in any winding: the material is double-sided).
fn triangle(parts: &mut Parts, name: &str, corners: [DVec3; 3], material: usize) {
    parts.meshes.push(Mesh {
        name: name.to_owned(),
        vertices: corners
            .iter()
            .map(|c| Vertex {
                position: c.as_vec3().to_array(),
                normal: [0.0, 0.0, 1.0],
                uv: [0.0, 0.0],
                color: Vertex::WHITE,
                tangent: Vertex::NO_TANGENT,
                uv1: [0.0; 2],
            })
            .collect::<Vec<_>>()
            .into(),
        indices: vec![0, 1, 2].into(),
        material,
        transform: DMat4::IDENTITY,
    });
}

fn unlit(parts: &mut Parts, name: &str, rgb: [f32; 3]) -> usize {
    let m = parts.material(name, rgb, 1.0);
    parts.materials[m].unlit = true;
    parts.materials[m].double_sided = true;
    m
}

/// A grey background square with the odd triangles in front; `tiny` adds the two
/// sub-sample triangles, at pixel (8, 8)'s center and at its first sample (0.375, 0.125).
fn odd_triangles(tiny: bool) -> Scene {
    let mut parts = Parts::new();
    let grey = unlit(&mut parts, "grey", [0.25, 0.25, 0.25]);
    let white = unlit(&mut parts, "white", [1.0, 1.0, 1.0]);
    let red = unlit(&mut parts, "red", [1.0, 0.0, 0.0]);
    let (a, b) = (world(0.0, 0.0, 0.0), world(f64::from(N), f64::from(N), 0.0));
    triangle(&mut parts, "bg 1", [a, DVec3::new(b.x, a.y, 0.0), b], grey);
    triangle(&mut parts, "bg 2", [a, b, DVec3::new(a.x, b.y, 0.0)], grey);
    // Zero area: collinear, and a point.
    let p = world(20.5, 20.5, 1.0);
    triangle(
        &mut parts,
        "collinear",
        [p, p + DVec3::X, p + 2.0 * DVec3::X],
        white,
    );
    triangle(&mut parts, "point", [p, p, p], white);
    if tiny {
        let d = 0.01;
        for (name, (cx, cy)) in [("no sample", (8.5, 8.5)), ("one sample", (8.375, 8.125))] {
            triangle(
                &mut parts,
                name,
                [
                    world(cx - d, cy - d, 1.0),
                    world(cx + d, cy - d, 1.0),
                    world(cx, cy + d, 1.0),
                ],
                white,
            );
        }
    }
    // Much larger than the view, in the lower right quarter only (its hypotenuse runs
    // through the view's center), and one crossing the camera plane.
    let huge = 1.0e6;
    triangle(
        &mut parts,
        "huge",
        [
            DVec3::new(-huge, -huge, 0.5),
            DVec3::new(huge, huge, 0.5),
            DVec3::new(huge, -huge, 0.5),
        ],
        red,
    );
    triangle(
        &mut parts,
        "behind the camera",
        [
            world(2.0, 30.0, 2.0),
            world(6.0, 30.0, 2.0),
            world(4.0, 26.0, 50.0),
        ],
        white,
    );
    parts.scene("odd triangles", camera())
}

fn all_finite(gpu: &Gpu, frame: &deferred_support::Frame, what: &str) {
    for target in ["hdr_lit", "albedo", "normal", "view_depth", "resolved"] {
        for (i, pixel) in frame.samples(gpu, target).iter().enumerate() {
            for (s, texel) in pixel.iter().enumerate() {
                assert!(
                    texel.iter().all(|c| c.is_finite()),
                    "{what}: {target} sample {s} of pixel {i} is {texel:?}"
                );
            }
        }
    }
}

#[test]
fn degenerate_tiny_and_huge_triangles_render_by_coverage() {
    let gpu = gpu();
    let run = |tiny: bool| {
        Render::new("deferred_msaa_4x.ron", "odd-triangles", (N, N))
            .with_scene(odd_triangles(tiny))
            .edit("outputs: [\"color\",", EXPORTS)
            .run(&gpu)
    };
    let (without, with) = (run(false), run(true));
    all_finite(&gpu, &with, "odd triangles");
    let (hdr_without, hdr_with) = (
        without.samples(&gpu, "hdr_lit"),
        with.samples(&gpu, "hdr_lit"),
    );
    let (resolved_without, resolved_with) = (
        without.samples(&gpu, "resolved"),
        with.samples(&gpu, "resolved"),
    );
    // What the tiny triangles changed, sample by sample.
    let changed: Vec<(u32, u32, usize)> = hdr_without
        .iter()
        .zip(&hdr_with)
        .enumerate()
        .flat_map(|(i, (a, b))| {
            (0..a.len())
                .filter(move |&s| a[s] != b[s])
                .map(move |s| (i as u32 % N, i as u32 / N, s))
        })
        .collect();
    assert_eq!(
        changed,
        vec![(8, 8, 0)],
        "the sub-sample triangles must change exactly sample 0 of pixel (8, 8)"
    );
    let pixel = (8 * N + 8) as usize;
    let (bg, fg) = (hdr_without[pixel][0], hdr_with[pixel][0]);
    let expected: Vec<f32> = (0..3).map(|c| (3.0 * bg[c] + fg[c]) / 4.0).collect();
    let got = resolved_with[pixel][0];
    assert!(
        (0..3).all(|c| (got[c] - expected[c]).abs() <= 1e-3),
        "pixel (8, 8) resolves to {got:?}, expected a quarter of the way from {bg:?} to \
         {fg:?}: {expected:?}"
    );
    let others_equal = (0..resolved_with.len())
        .filter(|&i| i != pixel)
        .all(|i| resolved_with[i] == resolved_without[i]);
    assert!(
        others_equal,
        "the sub-sample triangles changed other pixels"
    );
    // The huge triangle: every sample on its side of the hypotenuse (x > y in world,
    // away from the line by more than a sample's rounding) is red.
    let albedo = with.samples(&gpu, "albedo");
    let mut red = 0;
    for (i, pixel) in albedo.iter().enumerate() {
        let (px, py) = (f64::from(i as u32 % N) + 0.5, f64::from(i as u32 / N) + 0.5);
        let w = world(px, py, 0.0);
        if w.x - w.y > 0.2 && !(py > 25.0 && px < 7.0) {
            for s in pixel {
                assert_eq!(s[..3], [1.0, 0.0, 0.0], "pixel {i} of the huge triangle");
                red += 1;
            }
        }
    }
    assert!(
        red > 1000,
        "only {red} samples of the huge triangle checked"
    );
}

/// 1,000,000 triangles (a 1000 x 500 grid of quads over the view, each quad two
/// triangles) at 16x16: about 4,000 triangles per pixel, most covering no sample.
#[test]
fn a_million_triangles_render_at_16x16() {
    let gpu = gpu();
    let mut parts = Parts::new();
    let grey = parts.material("grey", [0.5, 0.5, 0.5], 0.5);
    let (columns, rows) = (1000u32, 500u32);
    let mut vertices = Vec::with_capacity(((columns + 1) * (rows + 1)) as usize);
    for j in 0..=rows {
        for i in 0..=columns {
            let (x, y) = (
                f64::from(i) / f64::from(columns) * 2.0 - 1.0,
                f64::from(j) / f64::from(rows) * 2.0 - 1.0,
            );
            let z = 0.1 * (x * 7.0).sin() * (y * 5.0).cos();
            vertices.push(Vertex {
                position: [x as f32, y as f32, z as f32],
                normal: [0.0, 0.0, 1.0],
                uv: [0.0, 0.0],
                color: Vertex::WHITE,
                tangent: Vertex::NO_TANGENT,
                uv1: [0.0; 2],
            });
        }
    }
    let mut indices = Vec::with_capacity((columns * rows * 6) as usize);
    for j in 0..rows {
        for i in 0..columns {
            let v = j * (columns + 1) + i;
            let w = v + columns + 1;
            indices.extend([v, v + 1, w + 1, v, w + 1, w]);
        }
    }
    assert_eq!(indices.len() / 3, 1_000_000);
    parts.meshes.push(Mesh {
        name: "grid".into(),
        vertices: vertices.into(),
        indices: indices.into(),
        material: grey,
        transform: DMat4::IDENTITY,
    });
    parts.lights.push(rgraph_scene::Light {
        name: "sun".into(),
        kind: rgraph_scene::LightKind::Directional,
        color: [1.0, 1.0, 1.0],
        intensity: 3.0,
        position: DVec3::ZERO,
        direction: rgraph_scene::glam::Vec3::new(0.0, 0.0, -1.0),
        range: None,
    });
    let scene = parts.scene("a million triangles", camera());
    let frame = Render::new("deferred_msaa_4x.ron", "million", (16, 16))
        .with_scene(scene)
        .edit("outputs: [\"color\",", EXPORTS)
        .run(&gpu);
    all_finite(&gpu, &frame, "a million triangles");
    let resolved = frame.samples(&gpu, "resolved");
    let lit = resolved
        .iter()
        .filter(|p| p[0][0] + p[0][1] + p[0][2] > 0.1)
        .count();
    assert_eq!(lit, 256, "every pixel of the grid is lit");
}
