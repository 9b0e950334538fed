//! Image-based lighting, the default lighting of files without lights, as every pipeline
//! renders it.
//!
//! The box scenes: a cube from -1 to 1 under an orthographic camera from above front right,
//! so three faces (normals +X, +Y, +Z) each fill a region of pixels that share one normal
//! and one view direction, lit by the neutral environment alone. Their expected radiance
//! comes from the CPU: the irradiance integral by quadrature (not the spherical harmonics
//! the shaders evaluate), and the split-sum terms of scene/src/prefilter.rs.

use crate::deferred_support;

use deferred_support::measure::pixels_within;
use deferred_support::scenes::Parts;
use deferred_support::{gpu, Render};
use rgraph_scene::glam::{DVec3, Vec3};
use rgraph_scene::{
    irradiance_integral, prefilter, split_sum, Camera, Environment, Lighting, Projection, Scene,
};

const SIZE: (u32, u32) = (64, 64);
const PIPELINES: [&str; 4] = [
    "deferred_msaa_4x.ron",
    "deferred_msaa_4x_tiled.ron",
    "deferred_per_sample_4x_tiled.ron",
    "forward_msaa_4x.ron",
];
const EYE: DVec3 = DVec3::new(3.0, 2.5, 4.0);
const HALF_VIEW: f64 = 2.2;

fn camera() -> Camera {
    Camera::look_at(
        "box camera",
        EYE,
        DVec3::ZERO,
        DVec3::Y,
        Projection::Orthographic {
            xmag: HALF_VIEW as f32,
            ymag: HALF_VIEW as f32,
            znear: 0.1,
            zfar: 20.0,
        },
    )
}

/// The cube with one material, lit by the environment of intensity 1 only.
fn box_scene(albedo: f32, metallic: f32, roughness: f32) -> (Parts, Scene) {
    let mut parts = Parts::new();
    let material = parts.material("box", [albedo; 3], roughness);
    parts.materials[material].metallic_factor = metallic;
    parts.cuboid("box", DVec3::splat(-1.0), DVec3::splat(1.0), material);
    let mut scene = parts.scene("environment box", camera());
    scene.environment = Some(Environment { intensity: 1.0 });
    (parts, scene)
}

/// For each pixel whose 3x3 neighbourhood of pixel centres all see the same face, that
/// face's normal and the point the pixel centre sees.
fn face_pixels(parts: &Parts) -> Vec<(u32, u32, DVec3, DVec3)> {
    let camera = camera();
    let forward = camera.forward();
    let right = forward.cross(DVec3::Y).normalize();
    let up = right.cross(forward);
    let face = |x: i64, y: i64| {
        let ndc = |c: i64, size: u32| (c as f64 + 0.5) / f64::from(size) * 2.0 - 1.0;
        let origin = EYE + right * ndc(x, SIZE.0) * HALF_VIEW - up * ndc(y, SIZE.1) * HALF_VIEW;
        parts.cast(origin, forward)
    };
    let mut pixels = Vec::new();
    for y in 1..i64::from(SIZE.1) - 1 {
        for x in 1..i64::from(SIZE.0) - 1 {
            let Some(hit) = face(x, y) else { continue };
            let same = |dx, dy| face(x + dx, y + dy).is_some_and(|h| h.polygon == hit.polygon);
            if (-1..=1).all(|dy| (-1..=1).all(|dx| same(dx, dy))) {
                let normal = parts.polygons[hit.polygon].normal;
                pixels.push((x as u32, y as u32, normal, hit.point));
            }
        }
    }
    pixels
}

/// What a surface of normal `n` and irradiance `irradiance` reflects from `point` toward the
/// camera at `eye`: lighting.wgsl's `environment_light` with the exact irradiance integral in place
/// of its spherical harmonics. The shaders light every camera as a point at its position
/// (the view vector is toward the eye, for orthographic cameras too), so this does.
fn expected(n: Vec3, irradiance: f32, point: DVec3, eye: DVec3, material: (f32, f32, f32)) -> f32 {
    let (albedo, metallic, roughness) = material;
    let v = (eye - point).normalize().as_vec3();
    let n_v = n.dot(v).clamp(1e-4, 1.0);
    let [a, b] = split_sum(n_v, roughness);
    let f0 = 0.04 + (albedo - 0.04) * metallic;
    let specular_albedo = f0 * a + b;
    let r = 2.0 * n.dot(v) * n - v;
    let diffuse =
        irradiance / std::f32::consts::PI * albedo * (1.0 - metallic) * (1.0 - specular_albedo);
    diffuse + prefilter(r, roughness) * specular_albedo
}

/// The worst relative error over the three faces' interior pixels, in every pipeline.
fn worst_relative_error(albedo: f32, metallic: f32, roughness: f32) -> f32 {
    let (parts, scene) = box_scene(albedo, metallic, roughness);
    let pixels = face_pixels(&parts);
    assert!(pixels.len() > 1000, "{} face pixels", pixels.len());
    let normals = [DVec3::X, DVec3::Y, DVec3::Z];
    let irradiance = normals.map(|n| irradiance_integral(n.as_vec3(), 512));
    let gpu = gpu();
    let mut worst = 0.0f32;
    for pipeline in PIPELINES {
        let hdr = Render::new(pipeline, "environment box", SIZE)
            .with_scene(scene.clone())
            .export_resolved()
            .run(&gpu)
            .hdr(&gpu, "resolved");
        for &(x, y, n, point) in &pixels {
            let face = normals
                .iter()
                .position(|&m| m == n)
                .expect("a face seen from the camera");
            let material = (albedo, metallic, roughness);
            let want = expected(n.as_vec3(), irradiance[face], point, EYE, material);
            let got = hdr[(y * SIZE.0 + x) as usize];
            for channel in &got[..3] {
                let error = (channel - want).abs() / want;
                assert!(
                    error < 0.03,
                    "{pipeline}: pixel ({x}, {y}) of the face of normal {n}: {got:?}, expected \
                     {want} (error {error})"
                );
                worst = worst.max(error);
            }
        }
    }
    worst
}

/// A rough white-ish Lambert box: the diffuse term is the irradiance integral within the
/// spherical harmonics' 3% (scene/src/environment.rs), plus a small specular term (worst
/// 1.8% on lavapipe).
#[test]
fn a_rough_dielectric_reflects_the_irradiance_integral_within_3_percent() {
    let worst = worst_relative_error(0.5, 0.0, 1.0);
    eprintln!("rough dielectric: worst relative error {worst}");
}

/// A mirror-like metal reflects the environment's radiance along the reflection, read from
/// the prefiltered cube map's first level (filtered between its 32x32 texels).
#[test]
fn a_smooth_metal_reflects_the_environment_within_3_percent() {
    let worst = worst_relative_error(0.8, 1.0, 0.0);
    eprintln!("smooth metal: worst relative error {worst}");
}

/// A white Lambert (roughness 1, dielectric) sphere lit by the environment alone: at every
/// pixel whose normal faces the camera (n.v above 0.3, away from the silhouette's MSAA
/// edge and the tessellation's flattest view), the radiance is the irradiance integral at
/// that normal (plus the small specular term) within 4% (worst 3.75% on lavapipe, where
/// the normal points down and sideways, toward the studio's darker floor): the spherical
/// harmonics' error, the smooth normals of a 48x24 sphere and the G-buffer's encodings
/// together.
#[test]
fn a_white_lambert_sphere_reflects_the_irradiance_integral_within_4_percent() {
    let spheres = Scene::load("builtin:spheres").unwrap();
    // The first sphere (the ground is mesh 0), alone, white and rough.
    let mut sphere = spheres.meshes[1].clone();
    sphere.material = 0;
    let center = sphere.transform.transform_point3(DVec3::ZERO);
    let radius = sphere.transform.x_axis.truncate().length();
    let mut parts = Parts::new();
    parts.material("white", [1.0; 3], 1.0);
    parts.meshes.push(sphere);
    let eye = center + DVec3::new(0.0, 0.5, 4.0) * radius;
    let camera = Camera::look_at(
        "sphere camera",
        eye,
        center,
        DVec3::Y,
        Projection::Orthographic {
            xmag: (1.2 * radius) as f32,
            ymag: (1.2 * radius) as f32,
            znear: 0.1,
            zfar: 100.0,
        },
    );
    let forward = camera.forward();
    let right = forward.cross(DVec3::Y).normalize();
    let up = right.cross(forward);
    let mut scene = parts.scene("environment sphere", camera);
    scene.environment = Some(Environment { intensity: 1.0 });
    let gpu = gpu();
    let hdr = Render::new("deferred_msaa_4x_tiled.ron", "environment sphere", SIZE)
        .with_scene(scene)
        .export_resolved()
        .run(&gpu)
        .hdr(&gpu, "resolved");
    let (mut checked, mut worst) = (0, 0.0f32);
    for y in 0..SIZE.1 {
        for x in 0..SIZE.0 {
            let ndc = |c: u32, size: u32| (f64::from(c) + 0.5) / f64::from(size) * 2.0 - 1.0;
            let origin = eye + (right * ndc(x, SIZE.0) - up * ndc(y, SIZE.1)) * 1.2 * radius;
            // Where the ray meets the sphere, if it does.
            let to_center = center - origin;
            let along = to_center.dot(forward);
            let miss2 = to_center.length_squared() - along * along;
            if miss2 >= radius * radius {
                continue;
            }
            let point = origin + forward * (along - (radius * radius - miss2).sqrt());
            let n = ((point - center) / radius).as_vec3();
            let v = (eye - point).normalize().as_vec3();
            if n.dot(v) < 0.3 {
                continue;
            }
            let irradiance = irradiance_integral(n, 128);
            let want = expected(n, irradiance, point, eye, (1.0, 0.0, 1.0));
            let got = hdr[(y * SIZE.0 + x) as usize][0];
            let error = (got - want).abs() / want;
            assert!(
                error < 0.04,
                "pixel ({x}, {y}), normal {n}: {got}, expected {want}"
            );
            worst = worst.max(error);
            checked += 1;
        }
    }
    assert!(checked > 1000, "{checked} pixels checked");
    eprintln!("white sphere: worst relative error {worst} over {checked} pixels");
}

/// The default lighting (environment and headlight) of a half-metallic box, whose
/// silhouette is an MSAA edge against the background, renders alike in the fragment and
/// compute light paths, per pixel (per sample on edges) and per sample, and in the forward
/// path: within 2/255 on 99% of pixels.
#[test]
fn every_pipeline_renders_the_default_lighting_alike() {
    let (_, scene) = box_scene(0.7, 0.5, 0.4);
    let scene = scene.lit(Lighting::Default);
    assert!(scene.environment.is_some() && scene.lights.len() == 1);
    let gpu = gpu();
    let image = |pipeline| {
        Render::new(pipeline, "environment box", (96, 96))
            .with_scene(scene.clone())
            .run(&gpu)
            .image(&gpu, "color")
    };
    let pairs = [
        ("deferred_msaa_4x.ron", "deferred_msaa_4x_tiled.ron"),
        ("deferred_msaa_4x.ron", "forward_msaa_4x.ron"),
        (
            "deferred_per_sample_4x.ron",
            "deferred_per_sample_4x_tiled.ron",
        ),
    ];
    for (a, b) in pairs {
        let (first, second) = (image(a), image(b));
        let within = pixels_within(&first, &second, 2);
        let share = within as f64 / first.pixels.len() as f64;
        assert!(share >= 0.99, "{b} against {a}: {share} within 2/255");
    }
}

/// `Lighting` decides which lights a scene keeps and whether it gets the defaults.
#[test]
fn lighting_modes_keep_replace_or_add_the_defaults() {
    let file = "scene/tests/fixtures/hierarchy_embedded.gltf";
    let unlit_file = Scene::load(file).unwrap();
    assert!(unlit_file.lights.is_empty() && unlit_file.environment.is_none());
    let auto = unlit_file.clone().lit(Lighting::Auto);
    assert!(auto.environment.is_some());
    assert_eq!(auto.lights.len(), 1);
    let warning = auto.warnings.last().unwrap();
    assert!(
        warning.contains("it has no lights; lit by the default lighting"),
        "{warning}"
    );
    let file_only = unlit_file.lit(Lighting::File);
    assert!(file_only.lights.is_empty() && file_only.environment.is_none());

    let spheres = Scene::load("builtin:spheres").unwrap();
    let own = spheres.lights.len();
    assert!(own > 0);
    assert_eq!(spheres.clone().lit(Lighting::Auto), spheres);
    let both = spheres.clone().lit(Lighting::Both);
    assert_eq!(
        (both.lights.len(), both.ambient),
        (own + 1, spheres.ambient)
    );
    let default = spheres.lit(Lighting::Default);
    assert_eq!((default.lights.len(), default.ambient), (1, [0.0; 3]));
    assert!(default.environment.is_some());
}
