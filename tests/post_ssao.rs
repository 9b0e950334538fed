//! Screen-space ambient occlusion (`ssao`, `ssao_blur`, passes/ssao.rs) in
//! pipelines/deferred_msaa_4x_ssao.ron: a flat plane is not occluded at all (the image is
//! deferred_msaa_4x.ron's, bit for bit), the floor of a right-angle corner is darkened as
//! the cosine-weighted visibility within the radius says (at full and half resolution),
//! AO never brightens, the tiled light pass applies it as the fragment passes do, and bad
//! parameters and sizes are refused.

use std::f64::consts::PI;

use rgraph_core::file::{load_str_with, GraphParams, Registry};
use rgraph_scene::glam::{DMat4, DVec3, DVec4};
use rgraph_scene::{Camera, DepthConvention, Projection, Scene};

use crate::deferred_support::measure::pixels_within;
use crate::deferred_support::scenes::Parts;
use crate::deferred_support::{gpu, Image, Render};

const PIPELINE: &str = "deferred_msaa_4x_ssao.ron";
const PLAIN: &str = "deferred_msaa_4x.ron";
const SIZE: (u32, u32) = (96, 96);
/// The pipeline's SSAO radius, world units.
const RADIUS: f64 = 0.5;

fn camera(eye: DVec3, target: DVec3) -> Camera {
    Camera::look_at(
        "camera",
        eye,
        target,
        DVec3::Y,
        Projection::Perspective {
            yfov: 0.9,
            znear: 0.1,
            zfar: Some(100.0),
        },
    )
}

/// A grey floor (its top face at y = 0 for z > 0) and, with `wall`, a wall rising from
/// it (its front face at z = 0), both far larger than the view, under ambient light only.
fn corner(wall: bool) -> (Parts, Scene) {
    let mut parts = Parts::new();
    let grey = parts.material("grey", [0.5; 3], 0.8);
    parts.cuboid(
        "floor",
        DVec3::new(-20.0, -1.0, 0.0),
        DVec3::new(20.0, 0.0, 20.0),
        grey,
    );
    if wall {
        parts.cuboid(
            "wall",
            DVec3::new(-20.0, 0.0, -1.0),
            DVec3::new(20.0, 20.0, 0.0),
            grey,
        );
    }
    parts.ambient = [1.0; 3];
    let scene = parts.scene(
        "corner",
        camera(DVec3::new(0.3, 1.6, 2.6), DVec3::new(0.0, 0.2, 0.0)),
    );
    (parts, scene)
}

fn render<'a>(pipeline: &'a str, scene: &Scene) -> Render<'a> {
    Render::new(pipeline, "corner", SIZE).with_scene(scene.clone())
}

/// The linear AO of each pixel of `debug.ao` (grey, sRGB-encoded).
fn ao_of(image: &Image) -> Vec<f64> {
    image
        .pixels
        .iter()
        .map(|p| {
            let c = f64::from(p[0]) / 255.0;
            if c <= 0.04045 {
                c / 12.92
            } else {
                ((c + 0.055) / 1.055).powf(2.4)
            }
        })
        .collect()
}

/// The floor of a flat plane has nothing above it: AO is exactly 1 everywhere, and the
/// frame is deferred_msaa_4x.ron's, bit for bit.
#[test]
fn ssao_of_a_flat_plane_is_one() {
    let gpu = gpu();
    let (_, scene) = corner(false);
    let images = render(PIPELINE, &scene).read(&gpu, &["debug.ao", "color"]);
    let not_one = images[0].pixels.iter().filter(|p| p[0] != 255).count();
    assert_eq!(not_one, 0, "{not_one} pixels of the plane are occluded");
    let plain = render(PLAIN, &scene).read(&gpu, &["color"]);
    let same = pixels_within(&images[1], &plain[0], 0);
    assert_eq!(
        same,
        images[1].pixels.len(),
        "SSAO changed a flat plane's frame"
    );
}

/// The cosine-weighted visibility of a point on the floor `d` from the wall, counting
/// only occluders within the radius: 1 minus the projected solid angle of the directions
/// that meet the wall within [`RADIUS`], over pi (midpoint quadrature).
fn corner_visibility(d: f64) -> f64 {
    const N: usize = 400;
    let mut blocked = 0.0;
    for i in 0..N {
        let theta = (i as f64 + 0.5) / N as f64 * PI / 2.0;
        for j in 0..N {
            // phi from the direction straight at the wall.
            let phi = (j as f64 + 0.5) / N as f64 * 2.0 * PI;
            let toward = theta.sin() * phi.cos();
            if toward > 0.0 && d / toward <= RADIUS {
                blocked += theta.cos() * theta.sin();
            }
        }
    }
    let cell = (PI / 2.0 / N as f64) * (2.0 * PI / N as f64);
    1.0 - blocked * cell / PI
}

/// The ray through the center of pixel (x, y), as the GPU projects.
fn ray(camera: &Camera, x: u32, y: u32) -> (DVec3, DVec3) {
    let aspect = SIZE.0 as f32 / SIZE.1 as f32;
    let view_proj =
        camera.projection_matrix(aspect, DepthConvention::ReversedZ) * camera.view_rotation();
    let inverse: DMat4 = view_proj.as_dmat4().inverse();
    let ndc = (
        (f64::from(x) + 0.5) / f64::from(SIZE.0) * 2.0 - 1.0,
        1.0 - (f64::from(y) + 0.5) / f64::from(SIZE.1) * 2.0,
    );
    let unproject = |depth: f64| {
        let h = inverse * DVec4::new(ndc.0, ndc.1, depth, 1.0);
        h.truncate() / h.w
    };
    let (near, farther) = (unproject(1.0), unproject(0.5));
    (camera.position + near, (farther - near).normalize())
}

/// How the AO of the floor at a right-angle corner compares with the visibility the
/// geometry gives at the point each pixel sees.
struct CornerFit {
    /// Floor pixels within the radius (and the blur) of the wall.
    count: usize,
    mean: f64,
    /// The largest error, where, and how far from the wall.
    worst: (f64, u32, u32, f64),
    /// The AO of floor pixels less than 0.03 from the wall.
    crease: Vec<f64>,
}

/// Renders the corner (SSAO at half resolution with `half`) and fits its AO. Floor
/// pixels beyond the radius and the blur must be exactly 1.
fn corner_fit(half: bool) -> CornerFit {
    let gpu = gpu();
    let (parts, scene) = corner(true);
    let mut render = render(PIPELINE, &scene);
    if half {
        render = render.edit(HALF.0, HALF.1);
    }
    let images = render.read(&gpu, &["debug.ao"]);
    let ao = ao_of(&images[0]);
    let blur = if half { 0.5 } else { 0.3 };
    let mut fit = CornerFit {
        count: 0,
        mean: 0.0,
        worst: (0.0, 0, 0, 0.0),
        crease: Vec::new(),
    };
    for y in 4..SIZE.1 - 4 {
        for x in 4..SIZE.0 - 4 {
            let (origin, dir) = ray(&scene.camera, x, y);
            let Some(hit) = parts.cast(origin, dir) else {
                continue;
            };
            let normal = parts.polygons[hit.polygon].normal;
            // Floor points: the distance to the wall.
            if normal.y < 0.99 {
                continue;
            }
            let d = hit.point.z;
            let got = ao[(y * SIZE.0 + x) as usize];
            if d > RADIUS + blur {
                assert_eq!(got, 1.0, "({x}, {y}), {d:.2} from the wall, is occluded");
                continue;
            }
            if d < 0.03 {
                fit.crease.push(got);
            }
            let error = (got - corner_visibility(d)).abs();
            fit.mean += error;
            fit.count += 1;
            if error > fit.worst.0 {
                fit.worst = (error, x, y, d);
            }
        }
    }
    fit.mean /= fit.count.max(1) as f64;
    println!(
        "{} floor pixels within the radius: mean error {:.4}, worst {:.4} at ({}, {}) \
         {:.3} from the wall; crease {:?}",
        fit.count, fit.mean, fit.worst.0, fit.worst.1, fit.worst.2, fit.worst.3, fit.crease
    );
    assert!(
        fit.count > 50,
        "only {} floor pixels near the wall",
        fit.count
    );
    assert!(!fit.crease.is_empty(), "no pixel at the crease");
    fit
}

/// The pipeline's raw AO at half the G-buffer's size.
const HALF: (&str, &str) = (
    r#""ao_raw": Texture(format: "r8unorm", when"#,
    r#""ao_raw": Texture(format: "r8unorm", size: Relative(0.5), when"#,
);

/// The floor at a right-angle corner: each pixel's AO against the visibility the
/// geometry gives at the point it sees (GTAO with a hard radius integrates exactly that
/// for a floor and a wall; the slices, steps and blur leave a bounded error): within
/// 0.02 on average and 0.12 at worst (measured on lavapipe: 0.0071 and 0.080), about 1/2
/// at the crease, and exactly 1 beyond the radius and the blur.
#[test]
fn ssao_darkens_a_right_angle_corner_by_its_visibility() {
    let fit = corner_fit(false);
    assert!(fit.mean < 0.02, "mean error {:.4}", fit.mean);
    assert!(fit.worst.0 < 0.12, "worst error {:?}", fit.worst);
    for got in fit.crease {
        assert!((0.45..0.63).contains(&got), "AO {got:.3} at the crease");
    }
}

/// At half resolution (the raw AO at half the G-buffer's size, upsampled by the blur's
/// depth weights) a plane is still exactly 1, and the corner is within 0.03 on average
/// and 0.2 at worst, the crease between 0.45 and 0.75 (measured on lavapipe: 0.012 and
/// 0.18, the crease 0.57 to 0.71: a texel's AO is its block's top-left pixel's, up to a
/// pixel farther from the wall).
#[test]
fn ssao_at_half_resolution_fits_the_corner_and_leaves_a_plane_alone() {
    let fit = corner_fit(true);
    assert!(fit.mean < 0.03, "mean error {:.4}", fit.mean);
    assert!(fit.worst.0 < 0.2, "worst error {:?}", fit.worst);
    for got in fit.crease {
        assert!((0.45..0.75).contains(&got), "AO {got:.3} at the crease");
    }
    let (_, plane) = corner(false);
    let images = render(PIPELINE, &plane)
        .edit(HALF.0, HALF.1)
        .read(&gpu(), &["debug.ao"]);
    let not_one = images[0].pixels.iter().filter(|p| p[0] != 255).count();
    assert_eq!(not_one, 0, "{not_one} pixels of the plane are occluded");
}

/// AO only darkens: every pixel of the resolved HDR image with SSAO is at most the one
/// without, channel by channel, on scenes with ambient and environment light, and some
/// pixels are darker.
#[test]
fn ssao_never_brightens() {
    let gpu = gpu();
    for scene in ["builtin:dense", "builtin:spheres"] {
        let hdr = |pipeline| {
            Render::new(pipeline, scene, SIZE)
                .export_resolved()
                .run(&gpu)
                .hdr(&gpu, "resolved")
        };
        let (with, without) = (hdr(PIPELINE), hdr(PLAIN));
        let brighter = (with.iter().zip(&without))
            .filter(|(a, b)| (0..3).any(|c| a[c] > b[c]))
            .count();
        assert_eq!(brighter, 0, "{scene}: SSAO brightened {brighter} pixels");
        let darker = (with.iter().zip(&without))
            .filter(|(a, b)| (0..3).any(|c| a[c] < b[c]))
            .count();
        assert!(darker > 0, "{scene}: SSAO darkened nothing");
    }
}

/// The tiled light pass with the same `ao` input renders the fragment passes' image
/// within 1/255 on at least 99.5% of the pixels, as the twins without SSAO do
/// (tests/deferred_tiled.rs).
#[test]
fn tiled_lighting_applies_ssao_as_the_fragment_passes_do() {
    let gpu = gpu();
    let tiled = Render::new("deferred_msaa_4x_tiled.ron", "builtin:dense", SIZE)
        .edit(
            r#"        "resolved_hdr": Texture(format: "rgba16float"),"#,
            r#"        "resolved_hdr": Texture(format: "rgba16float"),
        "ao_raw": Texture(format: "r8unorm"), "ao": Texture(format: "r8unorm"),"#,
        )
        .edit(
            r#"        (
            name: "light tiled","#,
            r#"        (name: "ssao", plugin: "ssao",
         inputs: { "normal": "normal", "view_depth": "view_depth" }, outputs: { "ao": "ao_raw" }),
        (name: "ssao blur", plugin: "ssao_blur",
         inputs: { "raw": "ao_raw", "view_depth": "view_depth" }, outputs: { "ao": "ao" }),
        (
            name: "light tiled","#,
        )
        .edit(
            r#""depth": "depth", "hdr": "hdr",
                "shadows": "shadow_atlas", "specular""#,
            r#""depth": "depth", "hdr": "hdr", "ao": "ao",
                "shadows": "shadow_atlas", "specular""#,
        )
        .read(&gpu, &["color"]);
    let fragment = Render::new(PIPELINE, "builtin:dense", SIZE).read(&gpu, &["color"]);
    let plain = Render::new(PLAIN, "builtin:dense", SIZE).read(&gpu, &["color"]);
    let total = tiled[0].pixels.len();
    let close = pixels_within(&tiled[0], &fragment[0], 1);
    assert!(
        close as f64 >= 0.995 * total as f64,
        "only {close} of {total} pixels within 1/255"
    );
    assert!(
        pixels_within(&tiled[0], &plain[0], 1) < close,
        "the tiled pass ignored the AO"
    );
}

/// Bad SSAO parameters are errors at load time naming the pass and the parameter.
#[test]
fn ssao_refuses_bad_parameters() {
    let mut registry = Registry::with_builtins();
    rgraph_passes::register(&mut registry, None);
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("pipelines")
        .join(PIPELINE);
    let text = std::fs::read_to_string(&path).expect("the SSAO pipeline");
    let params = "params: (radius: 0.5, directions: 4, steps: 4),";
    for (edit, pass, expected) in [
        (
            "params: (radius: 0.0, directions: 4, steps: 4),",
            "ssao",
            "SSAO's radius is 0, but must be finite and positive",
        ),
        (
            "params: (radius: 0.5, directions: 17, steps: 4),",
            "ssao",
            "SSAO's directions is 17, but must be from 1 to 16",
        ),
        (
            "params: (radius: 0.5, directions: 4, steps: 0),",
            "ssao",
            "SSAO's steps is 0, but must be from 1 to 32",
        ),
        (
            "params: (radius: 0.5, directions: 4, steps: 4, bias: 1.0),",
            "ssao",
            "SSAO's bias is 1, but must be at least 0 and below 1",
        ),
    ] {
        let edited = text.replace(params, edit);
        let Err(error) = load_str_with(&path, &edited, &registry, &GraphParams::new()) else {
            panic!("{edit} was accepted");
        };
        let error = error.to_string();
        assert!(
            error.contains(&format!("pass \"{pass}\"")) && error.contains(expected),
            "{edit}: {error}"
        );
    }
    let edited = text.replace(
        HALF.0,
        r#""ao_raw": Texture(format: "r8unorm", size: Relative(0.25), when"#,
    );
    let Err(error) = load_str_with(&path, &edited, &registry, &GraphParams::new()) else {
        panic!("AO at a quarter of the G-buffer's size was accepted");
    };
    let error = error.to_string();
    assert!(
        error.contains("pass \"ssao\"")
            && error.contains("slot \"ao\"")
            && error.contains("must be the G-buffer's size (Relative(1.0)) or half of it"),
        "{error}"
    );
    let edited = text.replace(
        r#"plugin: "ssao_blur",
            when: "!unlit_only & !no_lights",
            inputs"#,
        r#"plugin: "ssao_blur",
            when: "!unlit_only & !no_lights",
            params: (depth_tolerance: -1.0),
            inputs"#,
    );
    let Err(error) = load_str_with(&path, &edited, &registry, &GraphParams::new()) else {
        panic!("a negative depth tolerance was accepted");
    };
    assert!(
        error.to_string().contains("depth_tolerance is -1"),
        "{error}"
    );
}
