//! Particles (seed 001) end to end on lavapipe: the particle pipelines on a stage built in
//! code, an unlit grey backdrop at z = -5 filling the view and an unlit blue panel at
//! z = 0, under an orthographic camera at z = 10 whose view is 2 units across, so at
//! 128x128 a unit is 64 pixels, world (x, y) lies at pixel ((x + 1) * 64, (1 - y) * 64)
//! and view depth is 10 - z. The scene's ambient is 1, so a blended particle's colour is
//! its albedo.

use crate::deferred_support::scenes::Parts;
use crate::deferred_support::{gpu, Image, Render};
use rgraph_core::file::{load_file_with, load_str_with, GraphParams, Registry};
use rgraph_core::gpu::Gpu;
use rgraph_core::CompileOptions;
use rgraph_scene::glam::DVec3;
use rgraph_scene::{Camera, Particle, ParticleEmitter, Projection, Scene};

const SIZE: (u32, u32) = (128, 128);
/// One 8-bit step, the tolerance of exact expectations in linear HDR.
const STEP: f32 = 1.0 / 255.0;
const FULL: &str = "particles_full_res.ron";
const LOW: &str = "particles_low_res.ron";
const MIXED: &str = "particles_mixed_res.ron";

const GREY: [f32; 3] = [0.5, 0.5, 0.5];
const BLUE: [f32; 3] = [0.0, 0.0, 1.0];

/// The stage with a panel of half extents `half` and `particles` in one emitter.
fn stage(half: (f64, f64), particles: Vec<Particle>) -> Scene {
    turned_stage(half, 0.0, particles)
}

/// [`stage`] with the panel turned by `angle` radians about the view axis.
fn turned_stage(half: (f64, f64), angle: f64, particles: Vec<Particle>) -> Scene {
    let mut parts = Parts::new();
    let flat = |parts: &mut Parts, name, rgb| {
        let material = parts.material(name, rgb, 1.0);
        parts.materials[material].unlit = true;
        material
    };
    let grey = flat(&mut parts, "backdrop", GREY);
    let blue = flat(&mut parts, "panel", BLUE);
    let quad = |(x, y): (f64, f64), z| {
        vec![
            DVec3::new(-x, -y, z),
            DVec3::new(x, -y, z),
            DVec3::new(x, y, z),
            DVec3::new(-x, y, z),
        ]
    };
    parts.mesh("backdrop", &[quad((3.0, 3.0), -5.0)], grey);
    let (sin, cos) = angle.sin_cos();
    let turned: Vec<DVec3> = quad(half, 0.0)
        .into_iter()
        .map(|p| DVec3::new(p.x * cos - p.y * sin, p.x * sin + p.y * cos, p.z))
        .collect();
    parts.mesh("panel", &[turned], blue);
    parts.ambient = [1.0; 3];
    let projection = Projection::Orthographic {
        xmag: 1.0,
        ymag: 1.0,
        znear: 1.0,
        zfar: 20.0,
    };
    let camera = Camera::look_at(
        "front",
        DVec3::new(0.0, 0.0, 10.0),
        DVec3::ZERO,
        DVec3::Y,
        projection,
    );
    let mut scene = parts.scene("particle stage", camera);
    scene.emitters = vec![ParticleEmitter {
        name: "test".to_owned(),
        particles,
    }];
    scene.check_particles().expect("valid particles");
    scene
}

fn particle(position: [f64; 3], size: f32, color: [f32; 3], alpha: f32) -> Particle {
    Particle {
        position: DVec3::from_array(position),
        size,
        color,
        alpha,
        emissive: false,
    }
}

/// The pixel under world (x, y).
fn pixel(x: f64, y: f64) -> (u32, u32) {
    (((x + 1.0) * 64.0) as u32, ((1.0 - y) * 64.0) as u32)
}

/// The resolved HDR image (before tone mapping) of `pipeline` with `scene` and `params`.
fn resolved(gpu: &Gpu, pipeline: &str, scene: &Scene, params: &[(&str, u32)]) -> Vec<[f32; 4]> {
    let render = params.iter().fold(
        Render::new(pipeline, "particle stage", SIZE)
            .with_scene(scene.clone())
            .export_resolved(),
        |render, (name, value)| render.param(name, *value),
    );
    render.run(gpu).hdr(gpu, "resolved")
}

fn at(image: &[[f32; 4]], (x, y): (u32, u32)) -> [f32; 4] {
    image[(y * SIZE.0 + x) as usize]
}

/// The largest difference of any colour channel.
fn largest_difference(a: &[[f32; 4]], b: &[[f32; 4]]) -> f32 {
    a.iter()
        .zip(b)
        .flat_map(|(a, b)| (0..3).map(move |c| (a[c] - b[c]).abs()))
        .fold(0.0, f32::max)
}

/// How many pixels differ by more than `by` in some colour channel.
fn changed(a: &[[f32; 4]], b: &[[f32; 4]], by: f32) -> usize {
    a.iter()
        .zip(b)
        .filter(|(a, b)| (0..3).any(|c| (a[c] - b[c]).abs() > by))
        .count()
}

/// Overlapping particles of several colours and opacities in front of the panel and the
/// backdrop, one of them crossing the panel (soft), all `emissive` or none.
fn overlapping(emissive: bool) -> Vec<Particle> {
    let colors = [
        [0.9, 0.2, 0.1],
        [0.2, 0.8, 0.3],
        [0.9, 0.9, 0.2],
        [0.3, 0.3, 0.9],
    ];
    (0..12)
        .map(|i| {
            let t = i as f64 / 11.0;
            Particle {
                position: DVec3::new(-0.8 + 1.6 * t, 0.5 - t, -0.1 + 2.0 * (i % 3) as f64),
                size: 0.7 + 0.1 * (i % 4) as f32,
                color: colors[i % 4],
                alpha: 0.3 + 0.15 * (i % 5) as f32,
                emissive,
            }
        })
        .collect()
}

#[test]
fn at_scale_1_with_point_depth_the_composite_reproduces_full_resolution_blending() {
    let gpu = gpu();
    for emissive in [false, true] {
        let kind = if emissive {
            "additive"
        } else {
            "alpha-blended"
        };
        let scene = stage((0.6, 0.4), overlapping(emissive));
        let full = resolved(&gpu, FULL, &scene, &[]);
        let bare = resolved(&gpu, FULL, &stage((0.6, 0.4), Vec::new()), &[]);
        let drawn = changed(&full, &bare, 0.05);
        assert!(
            drawn > 4000,
            "{kind}: the particles changed only {drawn} pixels"
        );
        for pipeline in [LOW, MIXED] {
            let low = resolved(&gpu, pipeline, &scene, &[("scale", 1), ("depth_taps", 1)]);
            let worst = largest_difference(&low, &full);
            assert!(
                worst <= STEP,
                "{kind}, {pipeline} at scale 1: a channel differs by {worst} from full resolution"
            );
        }
    }
}

/// Red opaque-centred particles of diameter 0.3 at (x, 0, z).
fn red_at(spots: &[(f64, f64)]) -> Vec<Particle> {
    spots
        .iter()
        .map(|&(x, z)| particle([x, 0.0, z], 0.3, [1.0, 0.0, 0.0], 1.0))
        .collect()
}

#[test]
fn a_particle_behind_the_panel_is_hidden_and_one_in_front_is_not_at_every_scale() {
    let gpu = gpu();
    let half = (0.9, 0.6);
    let bare = resolved(&gpu, FULL, &stage(half, Vec::new()), &[]);
    // Both well inside the panel: 19 pixels from its edges, more than an 8x8 block and
    // the bilinear reach beyond it.
    let scene = stage(half, red_at(&[(-0.45, -1.0), (0.45, 1.0)]));
    let (behind, front) = (pixel(-0.45, 0.0), pixel(0.45, 0.0));
    let mut runs = vec![(FULL, 1, resolved(&gpu, FULL, &scene, &[]))];
    for scale in [1, 2, 4, 8] {
        for pipeline in [LOW, MIXED] {
            runs.push((
                pipeline,
                scale,
                resolved(&gpu, pipeline, &scene, &[("scale", scale)]),
            ));
        }
    }
    for (pipeline, scale, image) in runs {
        let hidden = at(&image, behind);
        assert!(
            (0..3).all(|c| (hidden[c] - at(&bare, behind)[c]).abs() <= STEP),
            "{pipeline} at scale {scale}: the particle behind the panel shows: {hidden:?}"
        );
        let shown = at(&image, front);
        assert!(
            shown[0] > 0.5 && shown[2] < 0.5,
            "{pipeline} at scale {scale}: the particle in front of the panel is not red: {shown:?}"
        );
    }
}

#[test]
fn soft_particles_fade_to_zero_at_the_intersection() {
    let gpu = gpu();
    // In front of the panel by 0 (touching it), 0.1 and 1 unit; softness 4 per unit
    // fades them to 0, 0.4 and 1.
    let scene = stage((0.9, 0.6), red_at(&[(-0.5, 0.0), (0.0, 0.1), (0.5, 1.0)]));
    let bare = resolved(&gpu, FULL, &stage((0.9, 0.6), Vec::new()), &[]);
    let images = [
        (FULL, resolved(&gpu, FULL, &scene, &[])),
        (
            LOW,
            resolved(&gpu, LOW, &scene, &[("scale", 1), ("depth_taps", 1)]),
        ),
    ];
    for (pipeline, image) in images {
        for (x, fade) in [(-0.5, 0.0), (0.0, 0.4), (0.5, 1.0)] {
            let centre = pixel(x, 0.0);
            // The pixel centre is half a pixel from the particle's: its soft texture
            // is 0.995 there.
            let alpha = 0.995 * fade;
            let [r, _, b, _] = at(&image, centre);
            assert!(
                (r - alpha).abs() < 0.01 && (b - (1.0 - alpha)).abs() < 0.01,
                "{pipeline}: a particle {fade} of the way faded in shows ({r}, {b}), not \
                 ({alpha}, {})",
                1.0 - alpha
            );
        }
        let touching = pixel(-0.5, 0.0);
        let (shown, there) = (at(&image, touching), at(&bare, touching));
        assert!(
            (0..3).all(|c| (shown[c] - there[c]).abs() <= STEP),
            "{pipeline}: the particle touching the panel shows: {shown:?} over {there:?}"
        );
    }
}

/// Pixels outside the small panel (of half side `half`, turned by [`TURN`]) where the full-resolution particle adds at least 0.2
/// in red but `image` less than 90% of it: where a foreground silhouette hides the
/// particle beyond the foreground.
const TURN: f64 = 0.5;

fn halo(image: &[[f32; 4]], full: &[[f32; 4]], bare: &[[f32; 4]], half: f64) -> usize {
    let panel = |x: u32, y: u32| {
        let (wx, wy) = ((x as f64 + 0.5) / 64.0 - 1.0, 1.0 - (y as f64 + 0.5) / 64.0);
        let (sin, cos) = TURN.sin_cos();
        let (u, v) = (wx * cos + wy * sin, -wx * sin + wy * cos);
        // Pixels the edge crosses count as the panel's.
        u.abs() <= half + 1.0 / 64.0 && v.abs() <= half + 1.0 / 64.0
    };
    (0..SIZE.0 * SIZE.1)
        .filter(|&i| !panel(i % SIZE.0, i / SIZE.0))
        .filter(|&i| {
            let i = i as usize;
            let added = full[i][0] - bare[i][0];
            added >= 0.2 && image[i][0] - bare[i][0] < 0.9 * added
        })
        .count()
}

#[test]
fn the_maximum_depth_downsample_removes_the_halo_point_sampling_leaves() {
    let gpu = gpu();
    // A small panel in front of one large particle that covers the view, turned so its
    // edges cross the off-screen blocks everywhere within them.
    let half = 0.3;
    let big = vec![particle([0.0, 0.0, -2.0], 4.0, [1.0, 0.0, 0.0], 1.0)];
    let scene = turned_stage((half, half), TURN, big);
    let bare = resolved(
        &gpu,
        FULL,
        &turned_stage((half, half), TURN, Vec::new()),
        &[],
    );
    let full = resolved(&gpu, FULL, &scene, &[]);
    assert_eq!(halo(&full, &full, &bare, half), 0);
    let count = |scale, taps| {
        let image = resolved(&gpu, LOW, &scene, &[("scale", scale), ("depth_taps", taps)]);
        halo(&image, &full, &bare, half)
    };
    // The seed's four samples (2x2) represent a 2x2 block fully and remove its halo;
    // at larger scales they leave part of it, and taps covering the block remove it.
    for scale in [2, 4, 8] {
        let (point, seed, every) = (count(scale, 1), count(scale, 2), count(scale, scale));
        eprintln!(
            "scale {scale}: halo pixels with point sampling {point}, the maximum of 2x2 \
             {seed}, of {scale}x{scale} {every}"
        );
        assert!(
            point > 20,
            "scale {scale}: point sampling left only {point} halo pixels"
        );
        assert!(
            seed < point,
            "scale {scale}: the seed's four samples leave {seed} of {point}"
        );
        assert_eq!(
            every, 0,
            "scale {scale}: the maximum of every pixel leaves {every}"
        );
    }
}

/// FLIP's mean error of `test` against `reference` (8-bit sRGB images).
fn flip(reference: &Image, test: &Image) -> f64 {
    let rgb = |image: &Image| {
        let bytes: Vec<u8> = image
            .pixels
            .iter()
            .flat_map(|p| [p[0], p[1], p[2]])
            .collect();
        nv_flip::FlipImageRgb8::with_data(image.width, image.height, &bytes)
    };
    let map = nv_flip::flip(
        rgb(reference),
        rgb(test),
        nv_flip::DEFAULT_PIXELS_PER_DEGREE,
    );
    let values = map.to_vec();
    values.iter().map(|&v| f64::from(v)).sum::<f64>() / values.len() as f64
}

#[test]
fn mixed_resolution_is_closer_to_full_resolution_than_low_resolution() {
    let gpu = gpu();
    let size = (192, 108);
    let scene = "builtin:smoke?count=1500";
    let color = |pipeline, scale| {
        Render::new(pipeline, scene, size)
            .param("scale", scale)
            .read(&gpu, &["color"])
            .remove(0)
    };
    let full = Render::new(FULL, scene, size)
        .read(&gpu, &["color"])
        .remove(0);
    for scale in [2, 4] {
        let (low, mixed) = (
            flip(&full, &color(LOW, scale)),
            flip(&full, &color(MIXED, scale)),
        );
        eprintln!("scale {scale}: FLIP against full resolution: low {low:.4}, mixed {mixed:.4}");
        assert!(
            low > 0.005,
            "scale {scale}: low resolution is full resolution ({low})"
        );
        assert!(
            mixed < 0.6 * low,
            "scale {scale}: mixed {mixed} is not clearly closer than low {low}"
        );
    }
}

/// The particle pipelines loaded with `params`, declared only (no host).
fn load(pipeline: &str, params: &[(&str, u32)]) -> Result<rgraph_core::file::LoadedGraph, String> {
    let mut registry = Registry::with_builtins();
    rgraph_passes::register(&mut registry, None);
    let params = params
        .iter()
        .fold(GraphParams::new(), |p, (name, value)| p.with(*name, *value));
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("pipelines")
        .join(pipeline);
    load_file_with(&path, &registry, &params).map_err(|e| e.to_string())
}

#[test]
fn bad_particle_parameters_are_errors_naming_the_pass() {
    for (params, expected) in [
        (
            vec![("pad", 5000)],
            "pass \"particles (off screen)\" (particles): pad 5000 is more than 4096 \
             multiply-adds per fragment",
        ),
        (
            vec![("depth_taps", 0)],
            "pass \"depth downsample\" (depth_downsample): taps 0 is not from 1 (point \
             sampling) to 8",
        ),
        (
            vec![("scale", 0)],
            "parameter \"scale\" is 0, but the size divisor of \"particle_depth\" must be 1 \
             or more",
        ),
    ] {
        let error = load(LOW, &params).err().expect("rejected");
        assert!(error.contains(expected), "{params:?}: {error}");
    }
    let mut registry = Registry::with_builtins();
    rgraph_passes::register(&mut registry, None);
    for edits in [
        (
            "softness: 4.0, pad: Param(name: \"pad\", default: 0)),\n            inputs: { \"depth\": \"particle_depth\" }",
            "softness: 0.0, pad: Param(name: \"pad\", default: 0)),\n            inputs: { \"depth\": \"particle_depth\" }",
            "softness 0 must be finite and positive",
        ),
        (
            "\"edges\": \"particle_edges\", \"resolved\"",
            "\"resolved\"",
            "slot \"stencil\"",
        ),
        (
            "inputs: { \"depth\": \"particle_depth\" }",
            "inputs: { \"depth\": \"depth\" }",
            "the particles are drawn at Relative(0.5): a full-resolution pass reads the \
             depth-stencil of its own size",
        ),
        (
            "params: (threshold: 1.0)",
            "params: (threshold: -1.0)",
            "threshold -1 must be finite and positive",
        ),
    ] {
        let (from, to, expected) = edits;
        // The edit lands where the pass is written: the pipeline or one of its parts.
        let edited = crate::common::edited_pipeline(MIXED, &[(from, to)]);
        let error = load_str_with(&edited.path, &edited.text, &registry, &GraphParams::new())
            .err()
            .expect("rejected")
            .to_string();
        assert!(error.contains(expected), "{to}: {error}");
    }
}

#[test]
fn explain_shows_the_off_screen_passes_at_their_size() {
    let loaded = load(MIXED, &[("scale", 4)]).unwrap();
    let plan = loaded
        .compile(&CompileOptions {
            output_size: (1280, 720),
            ..Default::default()
        })
        .unwrap();
    let text = rgraph_core::explain::text(&plan);
    // The depth downsample is a compute pass, dispatched over its output's size.
    assert!(text.contains(". depth downsample (compute)\n"), "{text}");
    for pass in ["particles (off screen)", "particle edges"] {
        let at = text.find(&format!(". {pass} (render)\n")).expect(pass);
        // After the line naming the part it came from, if it did.
        let next = text[at..]
            .lines()
            .skip(1)
            .find(|l| !l.trim_start().starts_with("from "));
        assert!(
            next == Some("         renders at 320x180, not the output's 1280x720"),
            "{pass}:\n{text}"
        );
    }
    let at = text.find(". composite particles (render)\n").unwrap();
    assert!(
        !text[at..].lines().nth(1).unwrap().contains("renders at"),
        "{text}"
    );
}

#[test]
fn a_moved_camera_redraws_the_particles_as_a_fresh_upload_does() {
    let gpu = gpu();
    let scene = stage((0.6, 0.4), overlapping(false));
    let mut frame = Render::new(FULL, "particle stage", SIZE)
        .with_scene(scene.clone())
        .export_resolved()
        .run(&gpu);
    let first = frame.hdr(&gpu, "resolved");
    let mut inputs = frame.inputs();
    // Round to the other side: the particles' back-to-front order reverses.
    inputs.camera = inputs.camera.orbited(DVec3::ZERO, std::f64::consts::PI);
    frame.next(inputs.clone());
    let moved = frame.hdr(&gpu, "resolved");
    let mut seen_from_there = scene;
    seen_from_there.camera = inputs.camera;
    let fresh = resolved(&gpu, FULL, &seen_from_there, &[]);
    let worst = largest_difference(&moved, &fresh);
    assert!(
        worst <= STEP,
        "the moved frame differs from a fresh one by {worst}"
    );
    assert!(
        changed(&moved, &first, 0.05) > 1000,
        "the view did not change"
    );
}

#[test]
fn render_warns_when_the_pipeline_leaves_the_scenes_particles_out() {
    let dir = std::env::temp_dir().join(format!("rgraph-particles-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("frame.png");
    let render = |pipeline: &str| {
        crate::cli_support::render_stderr(pipeline, "builtin:smoke?count=40", (64, 36), &out)
    };
    let warning = "warning: the scene has 40 particles, but pipelines/deferred_msaa_4x_tiled.ron \
                   has no `particles` pass to draw them";
    let stderr = render("pipelines/deferred_msaa_4x_tiled.ron");
    assert!(stderr.contains(warning), "{stderr}");
    let stderr = render("pipelines/particles_low_res.ron");
    assert!(!stderr.contains("particles, but"), "{stderr}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn an_engine_moves_and_adds_particles_through_the_frame_inputs() {
    let gpu = gpu();
    let half = (0.6, 0.4);
    let one = vec![particle([0.0, 0.0, 1.0], 0.5, [1.0, 0.0, 0.0], 0.8)];
    let mut frame = Render::new(LOW, "particle stage", SIZE)
        .with_scene(stage(half, one))
        .export_resolved()
        .run(&gpu);
    // Twelve where there was one: the buffer grows.
    let mut inputs = frame.inputs();
    inputs.emitters = std::sync::Arc::new(vec![ParticleEmitter {
        name: "simulated".to_owned(),
        particles: overlapping(true),
    }]);
    frame.next(inputs.clone());
    let moved = frame.hdr(&gpu, "resolved");
    let fresh = resolved(&gpu, LOW, &stage(half, overlapping(true)), &[]);
    let worst = largest_difference(&moved, &fresh);
    assert!(
        worst <= STEP,
        "the simulated particles differ from a fresh upload by {worst}"
    );

    let host = rgraph_passes::Host::new(
        std::sync::Arc::new(stage(half, Vec::new())),
        rgraph_passes::Overrides::default(),
    );
    let mut bad = overlapping(false);
    bad[3].size = -1.0;
    inputs.emitters = std::sync::Arc::new(vec![ParticleEmitter {
        name: "simulated".to_owned(),
        particles: bad,
    }]);
    assert_eq!(
        host.set_frame(inputs).unwrap_err().to_string(),
        "frame inputs: particle stage: emitter \"simulated\" particle 3: size -1 is not finite \
         and positive"
    );
}
