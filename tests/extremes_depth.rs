//! Extreme case 1 (issue 6), depth range: near plane 1e-3, far plane 1e7.
//!
//! - Extreme: two parallel planes facing the camera, 0.1% of their distance apart, at
//!   distances 1, 10, ..., 1e5 (a ratio of 1e8 between the far and near planes), drawn in
//!   both orders (so equal depths show whichever was drawn first).
//! - Expected: with reversed-Z float depth (the pipelines' default, depth32float-stencil8)
//!   the nearer plane wins every sample at every distance. Standard Z (the same pipeline
//!   with `reversed_z: false`) loses them to rounding from 1,000 on; that comparison is
//!   printed, not asserted. On lavapipe, of 8,192 samples per distance:
//!
//!   ```text
//!   distance  reversed Z: far plane, neither  standard Z: far plane, neither
//!        1e0                     0,       0                     0,       0
//!        1e1                     0,       0                     0,       0
//!        1e2                     0,       0                     0,       0
//!        1e3                     0,       0                  8192,       0
//!        1e4                     0,       0                  4096,       0
//!        1e5                     0,       0                     0,    8192
//!   ```
//! - Bound asserted: 0 samples of the farther plane, per distance and draw order, and the
//!   depth-stencil really is depth32float-stencil8 on the device.
//!
//! Also: the `compare` edge detector (its depth test is relative to the depth) marks the
//! same pixels for a scene scaled by 10 and by 10,000 (camera, near and far planes
//! included): 0 pixels differ.

use crate::deferred_support;

use deferred_support::scenes::Parts;
use deferred_support::{gpu, Render};
use rgraph_core::gpu::Gpu;
use rgraph_scene::glam::{DMat4, DVec3};
use rgraph_scene::{Camera, Projection, Scene};

const SIZE: (u32, u32) = (32, 32);
const NEAR: f32 = 1e-3;
const FAR: f32 = 1e7;
const DISTANCES: [f64; 6] = [1.0, 10.0, 100.0, 1e3, 1e4, 1e5];

/// A green plane at `distance` in front of a red one 0.1% farther, both filling the view
/// (unlit: the albedo target shows which won); `back_first` draws the red one first.
fn planes(distance: f64, back_first: bool) -> Scene {
    let mut parts = Parts::new();
    let green = parts.material("near", [0.0, 1.0, 0.0], 1.0);
    let red = parts.material("far", [1.0, 0.0, 0.0], 1.0);
    let plane = |z: f64| {
        let h = distance;
        vec![vec![
            DVec3::new(-h, -h, z),
            DVec3::new(h, -h, z),
            DVec3::new(h, h, z),
            DVec3::new(-h, h, z),
        ]]
    };
    let (front, back) = (plane(-distance), plane(-distance * 1.001));
    if back_first {
        parts.mesh("far", &back, red);
        parts.mesh("near", &front, green);
    } else {
        parts.mesh("near", &front, green);
        parts.mesh("far", &back, red);
    }
    let camera = Camera::look_at(
        "origin",
        DVec3::ZERO,
        DVec3::NEG_Z,
        DVec3::Y,
        Projection::Perspective {
            yfov: 1.0,
            znear: NEAR,
            zfar: Some(FAR),
        },
    );
    parts.scene("parallel planes", camera)
}

/// How many samples of the albedo target show the far (red) plane, and how many show
/// neither plane (standard Z rounds far planes' depth to 1, the cleared value, and the
/// `Less` test rejects them).
fn wrong_samples(gpu: &Gpu, scene: Scene, reversed: bool) -> (usize, usize) {
    let mut render = Render::new("deferred_msaa_4x.ron", "planes", SIZE)
        .with_scene(scene)
        .edit("outputs: [\"color\",", "outputs: [\"albedo\", \"color\",");
    if !reversed {
        render = render
            .edit(
                "plugin: \"gbuffer\",",
                "plugin: \"gbuffer\", params: (reversed_z: false),",
            )
            .edit(
                "(mode: sample_index)",
                "(mode: sample_index, reversed_z: false)",
            )
            .edit(
                "plugin: \"light_nonedge\",",
                "plugin: \"light_nonedge\", params: (reversed_z: false),",
            );
    }
    let albedo = render.run(gpu).samples(gpu, "albedo");
    let (mut red, mut green, mut samples) = (0, 0, 0);
    for texel in albedo.iter().flatten() {
        red += usize::from(texel[0] > 0.5 && texel[1] < 0.5);
        green += usize::from(texel[1] > 0.5 && texel[0] < 0.5);
        samples += 1;
    }
    (red, samples - red - green)
}

#[test]
fn planes_a_thousandth_apart_never_fight_with_reversed_z() {
    let gpu = gpu();
    assert!(
        gpu.adapter
            .features()
            .contains(wgpu::Features::DEPTH32FLOAT_STENCIL8),
        "{} lacks depth32float-stencil8: the pipelines fall back to 24-bit unorm depth, \
         which reversed Z does not help",
        gpu.info.name
    );
    let mut table =
        vec!["distance  reversed Z: far plane, neither  standard Z: far plane, neither".to_owned()];
    let mut failures = Vec::new();
    for distance in DISTANCES {
        let (mut reversed, mut standard) = ((0, 0), (0, 0));
        for back_first in [false, true] {
            let r = wrong_samples(&gpu, planes(distance, back_first), true);
            let s = wrong_samples(&gpu, planes(distance, back_first), false);
            reversed = (reversed.0 + r.0, reversed.1 + r.1);
            standard = (standard.0 + s.0, standard.1 + s.1);
        }
        table.push(format!(
            "{distance:>8.0e}  {:>20}, {:>7}  {:>20}, {:>7}",
            reversed.0, reversed.1, standard.0, standard.1
        ));
        if reversed != (0, 0) {
            failures.push(format!(
                "at {distance}: with reversed Z {} samples show the far plane, {} neither",
                reversed.0, reversed.1
            ));
        }
    }
    table.push(format!(
        "(of {} samples per distance: 2 draw orders of {}x{} pixels, 4 samples each)",
        2 * SIZE.0 * SIZE.1 * 4,
        SIZE.0,
        SIZE.1
    ));
    println!("{}", table.join("\n"));
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// `scene` with every length multiplied by `s`: meshes, lights, camera and its planes.
fn scaled(scene: &Scene, s: f64) -> Scene {
    let mut scene = scene.clone();
    for mesh in &mut scene.meshes {
        mesh.transform = DMat4::from_scale(DVec3::splat(s)) * mesh.transform;
    }
    for light in &mut scene.lights {
        light.position *= s;
        light.range = light.range.map(|r| r * s as f32);
        light.intensity *= (s * s) as f32;
    }
    scene.camera.position *= s;
    if let Projection::Perspective { znear, zfar, .. } = &mut scene.camera.projection {
        *znear *= s as f32;
        *zfar = zfar.map(|f| f * s as f32);
    }
    scene.bounds = scene
        .meshes
        .iter()
        .filter_map(|m| m.world_bounds())
        .reduce(|a, b| a.union(&b))
        .expect("the scene has meshes");
    scene
}

#[test]
fn compare_marks_the_same_edges_at_scale_10_and_10000() {
    let gpu = gpu();
    let base = Scene::load("builtin:dense").expect("builtin:dense loads");
    let edges = |s: f64| {
        let image = Render::new("deferred_msaa_4x.ron", "builtin:dense", (64, 64))
            .with_scene(scaled(&base, s))
            .read(&gpu, &["debug.edges"])
            .remove(0);
        image
            .pixels
            .iter()
            .map(|&p| p == [255, 0, 0, 255])
            .collect::<Vec<bool>>()
    };
    let (ten, ten_thousand) = (edges(10.0), edges(10_000.0));
    let marked = ten.iter().filter(|&&m| m).count();
    let differing: Vec<usize> = (0..ten.len())
        .filter(|&i| ten[i] != ten_thousand[i])
        .collect();
    println!(
        "compare marks {marked} pixels at scale 10, {} at 10,000; {} differ",
        ten_thousand.iter().filter(|&&m| m).count(),
        differing.len()
    );
    assert!(marked > 100, "only {marked} edge pixels at scale 10");
    assert!(
        differing.is_empty(),
        "{} pixels are marked at one scale only, e.g. {:?}",
        differing.len(),
        differing
            .iter()
            .take(8)
            .map(|i| (i % 64, i / 64))
            .collect::<Vec<_>>()
    );
}
