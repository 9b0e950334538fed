//! glTF alpha BLEND end to end, from files the tests write: square panels facing +z under
//! an orthographic camera 3 units in front whose view is 2.5 units across (so at 64x64 a
//! unit is 25.6 pixels), in front of an opaque background quad that fills the view.
//! Every pipeline that renders the lit scene draws BLEND meshes after lighting
//! (`transparent`, back to front) and composites them onto its resolved HDR image
//! (`composite_transparent`), compiled for the scene's features (they include `blend`).

use std::f32::consts::FRAC_PI_8;

use serde_json::json;

use crate::cli_support::{render_stderr, FORWARD_OPAQUE_ONLY};
use crate::deferred_support::measure::{pixel_diff, pixels_within};
use crate::deferred_support::{gpu, PipelineFile, Render};
use crate::gltf_writer::{fixture, temp_dir, Gltf};
use rgraph_core::file::{load_file, load_str, Registry};
use rgraph_core::{CompileOptions, DeviceProfile, Features};
use rgraph_scene::analysis::Features as SceneFeatures;
use rgraph_scene::glam::{DVec3, Vec3};
use rgraph_scene::{AlphaMode, Light, LightKind, Scene};

const SIZE: (u32, u32) = (64, 64);
/// One 8-bit step, the tolerance of exact expectations in linear HDR.
const STEP: f32 = 1.0 / 255.0;

/// Every pipeline file that renders the lit scene (visibility_msaa_4x.ron's branches for
/// CPU and GPU adapters both), with the name of the single-sampled HDR image it tone-maps
/// (`resolved`, or the lit HDR target in the files without a resolve).
const PIPELINES: [(PipelineFile, &str); 17] = [
    on_device("deferred_gbuffer_resolve_4x.ron", "hdr_lit"),
    on_device("deferred_msaa_4x.ron", "resolved"),
    on_device("deferred_msaa_4x_adaptive.ron", "resolved"),
    on_device("deferred_msaa_4x_centroid.ron", "resolved"),
    on_device("deferred_msaa_4x_coverage.ron", "resolved"),
    on_device("deferred_msaa_4x_sample_mask.ron", "resolved"),
    on_device("deferred_msaa_4x_tiled.ron", "resolved"),
    on_device("deferred_msaa_4x_tonemapped_resolve.ron", "resolved"),
    on_device("deferred_noaa.ron", "hdr_lit"),
    on_device("deferred_noaa_tiled.ron", "resolved"),
    on_device("deferred_onthefly_resolve_4x.ron", "resolved"),
    on_device("deferred_per_sample_4x.ron", "resolved"),
    on_device("deferred_per_sample_4x_tiled.ron", "resolved"),
    on_device("forward_msaa_4x.ron", "resolved"),
    on_device("reference_ssaa16.ron", "resolved"),
    on_device("visibility_msaa_4x.ron", "resolved"),
    (
        PipelineFile::gpu_branch("visibility_msaa_4x.ron"),
        "resolved",
    ),
];

/// File `name` compiled for the tests' adapter, with the HDR image `image` it tone-maps.
const fn on_device(
    name: &'static str,
    image: &'static str,
) -> (PipelineFile<'static>, &'static str) {
    (PipelineFile::for_device(name), image)
}

/// A square quad of the test scene.
#[derive(Clone, Copy)]
struct Panel {
    /// Where its centre is; it faces +z.
    center: [f32; 3],
    /// Half its side.
    half: f32,
    /// Turned about z by this many radians.
    angle: f32,
    /// Linear base colour and alpha.
    color: [f32; 4],
    blend: bool,
    unlit: bool,
}

impl Panel {
    /// An unlit panel of `color` centred at `z`.
    fn unlit(z: f32, half: f32, color: [f32; 4], blend: bool) -> Panel {
        Panel {
            center: [0.0, 0.0, z],
            half,
            angle: 0.0,
            color,
            blend,
            unlit: true,
        }
    }

    /// The unlit opaque background at z = -1, filling the view.
    fn background(color: [f32; 3]) -> Panel {
        Panel::unlit(-1.0, 2.0, [color[0], color[1], color[2], 1.0], false)
    }
}

/// The panels (each its own material, mesh and node, in the given order), the camera and
/// one point light up and to the left, written as `test`/panels.gltf; returns its path.
fn panels_file(test: &str, panels: &[Panel]) -> String {
    let mut gltf = Gltf::default();
    gltf.json["extensionsUsed"] = json!(["KHR_lights_punctual", "KHR_materials_unlit"]);
    for (i, panel) in panels.iter().enumerate() {
        let h = panel.half;
        let positions = gltf.floats(&[[-h, -h, 0.0], [h, -h, 0.0], [h, h, 0.0], [-h, h, 0.0]]);
        let normals = gltf.floats(&[[0.0, 0.0, 1.0]; 4]);
        let indices = gltf.indices_u16(&[0, 1, 2, 0, 2, 3]);
        let mut material = json!({
            "name": format!("panel {i}"),
            "pbrMetallicRoughness": {
                "baseColorFactor": panel.color, "metallicFactor": 0.0, "roughnessFactor": 0.5,
            },
            "alphaMode": if panel.blend { "BLEND" } else { "OPAQUE" },
        });
        if panel.unlit {
            material["extensions"] = json!({ "KHR_materials_unlit": {} });
        }
        let material = gltf.push("materials", material);
        let mesh = gltf.push(
            "meshes",
            json!({ "name": format!("panel {i}"), "primitives": [{
                "attributes": { "POSITION": positions, "NORMAL": normals },
                "indices": indices, "material": material,
            }] }),
        );
        let (sin, cos) = (panel.angle / 2.0).sin_cos();
        gltf.root(json!({
            "mesh": mesh, "translation": panel.center, "rotation": [0.0, 0.0, sin, cos],
        }));
    }
    let camera = gltf.push(
        "cameras",
        json!({ "type": "orthographic",
                "orthographic": { "xmag": 1.25, "ymag": 1.25, "znear": 0.1, "zfar": 10.0 } }),
    );
    gltf.root(json!({ "camera": camera, "translation": [0.0, 0.0, 3.0] }));
    let light = json!({ "type": "point", "color": [1.0, 0.9, 0.8], "intensity": 3.0 });
    gltf.json["extensions"] = json!({ "KHR_lights_punctual": { "lights": [light] } });
    gltf.root(json!({
        "translation": [-0.4, 0.5, 1.5], "extensions": { "KHR_lights_punctual": { "light": 0 } },
    }));
    let path = temp_dir(test).join("panels.gltf");
    gltf.write_embedded(&path);
    path.to_str().unwrap().to_owned()
}

fn load(file: &str) -> Scene {
    let scene = Scene::load(file).unwrap_or_else(|e| panic!("{e}"));
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    scene
}

/// `pipeline`'s single-sampled HDR image `image` of `scene`, compiled for its features.
fn hdr(pipeline: PipelineFile, image: &str, file: &str, scene: &Scene) -> Vec<[f32; 4]> {
    hdr_for(pipeline, image, file, scene, SceneFeatures::of(scene))
}

/// [`hdr`] compiled for `features`.
fn hdr_for(
    pipeline: PipelineFile,
    image: &str,
    file: &str,
    scene: &Scene,
    features: SceneFeatures,
) -> Vec<[f32; 4]> {
    let gpu = gpu();
    let export = format!("outputs: [\"{image}\", \"color\"");
    Render::new(pipeline, file, SIZE)
        .with_scene(scene.clone())
        .features(features.names())
        .edit("outputs: [\"color\"", &export)
        .run(&gpu)
        .hdr(&gpu, image)
}

/// Whether `got` is `want` within `tolerance` in every channel.
fn near(got: [f32; 3], want: [f32; 3], tolerance: f32) -> bool {
    got.iter()
        .zip(want)
        .all(|(g, w)| (g - w).abs() <= tolerance)
}

/// Pixels at least 2 from the border of the view's central square of half-side `half`
/// units, as (x, y).
fn inside(half: f32) -> impl Iterator<Item = (u32, u32)> {
    let (lo, hi) = (32.0 - half * 25.6 + 2.0, 32.0 + half * 25.6 - 2.0);
    (0..SIZE.1).flat_map(move |y| {
        (0..SIZE.0).filter_map(move |x| {
            let inside = |c: u32| (lo..hi).contains(&(c as f32 + 0.5));
            (inside(x) && inside(y)).then_some((x, y))
        })
    })
}

/// A BLEND panel shows what is behind it: an unlit red panel of alpha 0.5 over an unlit
/// blue background is (0.5, 0, 0.5) inside, within one 8-bit step, and the background
/// is untouched around it, in every pipeline, with 24-bit and with float depth. The glTF
/// loader keeps BLEND, without the warning it used to give.
#[test]
fn a_blend_panel_shows_what_is_behind_it_in_every_pipeline() {
    let file = panels_file(
        "blend_panel",
        &[
            Panel::background([0.0, 0.0, 1.0]),
            Panel::unlit(0.0, 0.5, [1.0, 0.0, 0.0, 0.5], true),
        ],
    );
    let scene = load(&file);
    assert_eq!(scene.materials[1].alpha_mode, AlphaMode::Blend);
    let shallow = SceneFeatures::of(&scene);
    assert!(shallow.blend);
    // Also with float depth, reversed-Z (as in a_blend_panel_behind_an_opaque_one_is_hidden).
    let float_depth = SceneFeatures {
        shallow_depth: false,
        ..shallow
    };
    for features in [shallow, float_depth] {
        for (pipeline, image) in PIPELINES {
            let hdr = hdr_for(pipeline, image, &file, &scene, features);
            let depth = format!("shallow_depth {}", features.shallow_depth);
            for (x, y) in inside(0.5) {
                let p = hdr[(y * SIZE.0 + x) as usize];
                assert!(
                    near([p[0], p[1], p[2]], [0.5, 0.0, 0.5], STEP),
                    "{pipeline}, {depth}: ({x}, {y}) is {p:?} inside the panel"
                );
            }
            for (x, y) in [(2, 2), (61, 2), (2, 61), (61, 61)] {
                let p = hdr[(y * SIZE.0 + x) as usize];
                assert_eq!(p[..3], [0.0, 0.0, 1.0], "{pipeline}, {depth}: ({x}, {y})");
            }
        }
    }
}

/// A blended surface behind an opaque one is hidden: the BLEND panel at z = 0 behind an
/// opaque green panel at z = 0.5 that covers it leaves the green exactly as the scene
/// without the BLEND panel shows it (green within an 8-bit step: a visibility buffer
/// interpolates the vertex colour it rebuilds), with the scene's 24-bit standard-Z depth
/// (`shallow_depth`) and with the general float depth, reversed-Z where the device has
/// depth32float-stencil8 (lavapipe has).
#[test]
fn a_blend_panel_behind_an_opaque_one_is_hidden() {
    let background = Panel::background([0.0, 0.0, 1.0]);
    let green = Panel::unlit(0.5, 0.7, [0.0, 1.0, 0.0, 1.0], false);
    let red = Panel::unlit(0.0, 0.5, [1.0, 0.0, 0.0, 0.5], true);
    let file = panels_file("blend_hidden", &[background, red, green]);
    let opaque_file = panels_file("blend_hidden_opaque", &[background, green]);
    let (scene, opaque) = (load(&file), load(&opaque_file));
    let shallow = SceneFeatures::of(&scene);
    assert!(shallow.shallow_depth);
    let float_depth = SceneFeatures {
        shallow_depth: false,
        ..shallow
    };
    for features in [shallow, float_depth] {
        let opaque_features = SceneFeatures {
            blend: false,
            ..features
        };
        for (pipeline, image) in PIPELINES {
            let hdr = hdr_for(pipeline, image, &file, &scene, features);
            let want = hdr_for(pipeline, image, &opaque_file, &opaque, opaque_features);
            for (x, y) in inside(0.5) {
                let at = (y * SIZE.0 + x) as usize;
                let p = hdr[at];
                let depth = format!("shallow_depth {}", features.shallow_depth);
                assert_eq!(p, want[at], "{pipeline}, {depth}: ({x}, {y})");
                assert!(
                    near([p[0], p[1], p[2]], [0.0, 1.0, 0.0], STEP),
                    "{pipeline}, {depth}: ({x}, {y}) is {p:?}"
                );
            }
        }
    }
}

/// Two overlapping BLEND panels composite back to front whichever the file lists first:
/// red (alpha 0.5) at z = 0.5 in front of blue (alpha 0.5) at z = 0, over white, is
/// 0.5 red + 0.5 (0.5 blue + 0.5 white) = (0.75, 0.25, 0.5); drawn the other way round
/// it would be (0.5, 0.25, 0.75).
#[test]
fn overlapping_blend_panels_composite_back_to_front_in_either_order() {
    let red = Panel::unlit(0.5, 0.5, [1.0, 0.0, 0.0, 0.5], true);
    let blue = Panel::unlit(0.0, 0.7, [0.0, 0.0, 1.0, 0.5], true);
    let white = Panel::background([1.0, 1.0, 1.0]);
    for (order, panels) in [
        ("near first", [white, red, blue]),
        ("far first", [white, blue, red]),
    ] {
        let file = panels_file(&format!("blend_order_{}", order.replace(' ', "_")), &panels);
        let scene = load(&file);
        for (pipeline, image) in PIPELINES {
            let hdr = hdr(pipeline, image, &file, &scene);
            for (x, y) in inside(0.5) {
                let p = hdr[(y * SIZE.0 + x) as usize];
                assert!(
                    near([p[0], p[1], p[2]], [0.75, 0.25, 0.5], STEP),
                    "{pipeline}, {order}: ({x}, {y}) is {p:?}"
                );
            }
        }
    }
}

/// A transparent pass that lists `accum` in its inputs draws over the accumulation
/// instead of clearing it, so layers of blended geometry (particles after meshes) share
/// one target: the panel accumulated twice is red of alpha 0.5 over itself over blue,
/// (0.75, 0, 0.25).
#[test]
fn a_second_transparent_pass_accumulates_over_the_first() {
    let file = panels_file(
        "blend_layers",
        &[
            Panel::background([0.0, 0.0, 1.0]),
            Panel::unlit(0.0, 0.5, [1.0, 0.0, 0.0, 0.5], true),
        ],
    );
    let scene = load(&file);
    let gpu = gpu();
    let hdr = Render::new("forward_msaa_4x.ron", &file, SIZE)
        .with_scene(scene.clone())
        .features(SceneFeatures::of(&scene).names())
        .edit(
            r#"outputs: { "accum": "transparent" },
        ),"#,
            r#"outputs: { "accum": "transparent" },
        ),
        (
            name: "transparent again",
            plugin: "transparent",
            when: "blend",
            inputs: { "depth": "depth", "accum": "transparent" },
            outputs: { "accum": "transparent_twice" },
        ),"#,
        )
        .edit(
            r#"inputs: { "accum": "transparent", "resolved": "opaque" },"#,
            r#"inputs: { "accum": "transparent_twice", "resolved": "opaque" },"#,
        )
        .export_resolved()
        .run(&gpu)
        .hdr(&gpu, "resolved");
    for (x, y) in inside(0.5) {
        let p = hdr[(y * SIZE.0 + x) as usize];
        assert!(
            near([p[0], p[1], p[2]], [0.75, 0.0, 0.25], STEP),
            "({x}, {y}) is {p:?}"
        );
    }
}

/// `extent: blended` (the shipped pipelines') begins the accumulation by a draw over the
/// blended meshes' rectangle instead of a clear (explain shows it overwritten, not
/// cleared), and the composite draws only there: with a panel in a corner of the view the
/// image is `extent: full`'s bit for bit and the pixels far from the panel are the
/// background exactly (the composite never reads the accumulation there, which wgpu
/// begins as zero: transmittance 0 would blacken them); with the panel out of view every
/// pixel is the background. Forward MSAA and the visibility buffer's GPU branch (whose
/// keys_depth the edit to `extent: full` turns full too).
#[test]
fn the_accumulation_begins_and_composites_over_the_blended_rectangle_only() {
    let panel = |x: f32| Panel {
        center: [x, 0.8, 0.0],
        ..Panel::unlit(0.0, 0.2, [1.0, 0.0, 0.0, 0.5], true)
    };
    let corner = panels_file(
        "blend_rect_corner",
        &[Panel::background([0.0, 0.0, 1.0]), panel(-0.8)],
    );
    let aside = panels_file(
        "blend_rect_aside",
        &[Panel::background([0.0, 0.0, 1.0]), panel(5.0)],
    );
    let blended = "params: (extent: blended)";
    let gpu = gpu();
    for pipeline in [
        PipelineFile::for_device("forward_msaa_4x.ron"),
        PipelineFile::gpu_branch("visibility_msaa_4x.ron"),
    ] {
        let render = |file: &str, extent: &'static str| {
            let scene = load(file);
            Render::new(pipeline, file, SIZE)
                .with_scene(scene.clone())
                .features(SceneFeatures::of(&scene).names())
                .edit(blended, extent)
                .export_resolved()
                .run(&gpu)
                .hdr(&gpu, "resolved")
        };
        let full = render(&corner, "params: (extent: full)");
        let rect = render(&corner, blended);
        let differences = crate::deferred_support::hdr_differences(
            &full,
            &rect,
            SIZE.0,
            ("extent: full", "extent: blended"),
        );
        assert!(
            differences.is_empty(),
            "{pipeline}: {} pixels differ, first {:?}",
            differences.len(),
            &differences[..differences.len().min(4)]
        );
        // The panel covers x, y in 6..16 (its centre 12 pixels from the top left corner).
        let p = rect[(11 * SIZE.0 + 11) as usize];
        assert!(
            near([p[0], p[1], p[2]], [0.5, 0.0, 0.5], STEP),
            "{pipeline}: {p:?}"
        );
        for (x, y) in [(40, 40), (61, 2), (2, 61), (61, 61)] {
            let p = rect[(y * SIZE.0 + x) as usize];
            assert_eq!(p[..3], [0.0, 0.0, 1.0], "{pipeline}: ({x}, {y})");
        }
        let out_of_view = render(&aside, blended);
        for (i, p) in out_of_view.iter().enumerate() {
            assert_eq!(p[..3], [0.0, 0.0, 1.0], "{pipeline}: pixel {i}");
        }
    }
    let explain = crate::cli_support::rgraph(&[
        "explain",
        "--pipeline",
        "pipelines/forward_msaa_4x.ron",
        "--scene",
        &corner,
        "--size",
        "64x64",
    ])
    .expect(0)
    .stdout;
    let shown = "color 0: transparent overwrite (not cleared)";
    assert!(explain.contains(shown), "no {shown:?} in:\n{explain}");
}

/// A lit BLEND panel (Lambert plus GGX under a point light, alpha 0.4, over a lit opaque
/// background) renders alike in deferred (fragment and tiled lighting) and forward: their
/// 8-bit images agree within 2/255 on at least 99% of pixels, and the panel is neither
/// the background alone nor opaque.
#[test]
fn a_lit_blend_panel_renders_alike_in_deferred_tiled_and_forward() {
    let lit = |center: [f32; 3], half: f32, color: [f32; 4], blend: bool| Panel {
        center,
        half,
        angle: FRAC_PI_8,
        color,
        blend,
        unlit: false,
    };
    let panel = lit([0.1, 0.0, 0.0], 0.6, [0.9, 0.5, 0.2, 0.4], true);
    let background = lit([0.0, 0.0, -1.0], 2.0, [0.3, 0.5, 0.8, 1.0], false);
    let file = panels_file("blend_lit", &[background, panel]);
    let scene = load(&file);
    let gpu = gpu();
    let pipelines = [
        "deferred_msaa_4x.ron",
        "deferred_msaa_4x_tiled.ron",
        "forward_msaa_4x.ron",
    ];
    let images: Vec<_> = pipelines
        .iter()
        .map(|pipeline| {
            Render::new(*pipeline, &file, SIZE)
                .with_scene(scene.clone())
                .features(SceneFeatures::of(&scene).names())
                .run(&gpu)
                .image(&gpu, "color")
        })
        .collect();
    for (pipeline, image) in pipelines.iter().zip(&images).skip(1) {
        let close = pixels_within(image, &images[0], 2);
        let total = image.pixels.len();
        assert!(
            close * 100 >= total * 99,
            "{pipeline} and {}: only {close} of {total} pixels within 2/255",
            pipelines[0]
        );
    }
    // The panel changes what is behind it, and lets it through.
    let mut opaque = scene.clone();
    opaque.materials[1].alpha_mode = AlphaMode::Opaque;
    let mut without = scene.clone();
    without.meshes.truncate(1);
    let color = |scene: &Scene| {
        Render::new(pipelines[0], &file, SIZE)
            .with_scene(scene.clone())
            .features(SceneFeatures::of(scene).names())
            .run(&gpu)
            .image(&gpu, "color")
            .at(32, 32)
    };
    let (blended, opaque, without) = (images[0].at(32, 32), color(&opaque), color(&without));
    assert!(
        pixel_diff(blended, opaque) > 8 && pixel_diff(blended, without) > 8,
        "blended {blended:?}, opaque {opaque:?}, background alone {without:?}"
    );
}

/// An MSAA edge of an opaque object in front of a BLEND panel is antialiased: along the
/// slanted edge of an opaque green panel covering half of a red BLEND panel (alpha 0.5,
/// over blue), pixels lie between green and the blended (0.5, 0, 0.5), many strictly
/// between, in the 4x pipelines, each the product of means the composite documents;
/// without MSAA none do.
#[test]
fn an_opaque_edge_in_front_of_a_blend_panel_is_antialiased() {
    let mut cover = Panel::unlit(0.5, 0.8, [0.0, 1.0, 0.0, 1.0], false);
    // Turned 22.5 degrees and moved left so its right edge crosses the centre slanted.
    cover.angle = FRAC_PI_8;
    cover.center = [-0.8, 0.0, 0.5];
    let file = panels_file(
        "blend_msaa_edge",
        &[
            Panel::background([0.0, 0.0, 1.0]),
            Panel::unlit(0.0, 0.6, [1.0, 0.0, 0.0, 0.5], true),
            cover,
        ],
    );
    let scene = load(&file);
    let (green, blended) = ([0.0, 1.0, 0.0], [0.5, 0.0, 0.5]);
    for (pipeline, image, expect_between) in [
        ("deferred_msaa_4x.ron", "resolved", true),
        ("deferred_msaa_4x_tiled.ron", "resolved", true),
        ("forward_msaa_4x.ron", "resolved", true),
        ("deferred_noaa.ron", "hdr_lit", false),
    ] {
        let hdr = hdr(pipeline.into(), image, &file, &scene);
        let mut between = 0;
        for (x, y) in inside(0.6) {
            let p = hdr[(y * SIZE.0 + x) as usize];
            let p = [p[0], p[1], p[2]];
            if near(p, green, STEP) || near(p, blended, STEP) {
                continue;
            }
            let within = (0..3).all(|c| {
                let (lo, hi) = (green[c].min(blended[c]), green[c].max(blended[c]));
                (lo - STEP..=hi + STEP).contains(&p[c])
            });
            assert!(within, "{pipeline}: ({x}, {y}) is {p:?}, outside the two");
            between += 1;
            // With k of the 4 samples green, the composite gives mean(hdr) * mean(T) +
            // mean(C): red (4 - k) / 8 as the exact mean, green and blue scaled by
            // mean(T) = (k + (4 - k) / 2) / 4 where the exact pixel has k / 4 and
            // (4 - k) / 8 (passes/transparent.rs states the difference).
            let k = 4.0 - 8.0 * p[0];
            assert!(
                (k - k.round()).abs() < 0.05,
                "{pipeline}: ({x}, {y}) is {p:?}"
            );
            let k = k.round();
            let transmittance = (k + (4.0 - k) / 2.0) / 4.0;
            let expected = [
                (4.0 - k) / 8.0,
                k / 4.0 * transmittance,
                (4.0 - k) / 4.0 * transmittance,
            ];
            assert!(
                near(p, expected, STEP),
                "{pipeline}: ({x}, {y}) is {p:?}, not {expected:?} for {k} green samples"
            );
        }
        if expect_between {
            assert!(
                between >= 20,
                "{pipeline}: only {between} edge pixels between"
            );
        } else {
            assert_eq!(between, 0, "{pipeline}: {between} pixels between");
        }
    }
}

/// Khronos' AlphaBlendModeTest (tests/fixtures/AlphaBlendModeTest, CC BY 4.0) renders in
/// the deferred, tiled and forward pipelines, and its BLEND material changes the image
/// against the same file with every BLEND material made OPAQUE. The file has no lights,
/// so the test adds an ambient term and a directional light to see it.
#[test]
fn alpha_blend_mode_test_renders_and_blend_differs_from_opaque() {
    let path = fixture_path();
    let mut scene = Scene::load(&path).unwrap_or_else(|e| panic!("{e}"));
    assert!(
        scene.warnings.iter().all(|w| !w.contains("BLEND")),
        "{:?}",
        scene.warnings
    );
    let blended = scene
        .materials
        .iter()
        .filter(|m| m.alpha_mode == AlphaMode::Blend)
        .count();
    assert_eq!(blended, 1, "MatBlend");
    scene.ambient = [0.3; 3];
    scene.lights.push(Light {
        name: "test sun".to_owned(),
        kind: LightKind::Directional,
        color: [1.0; 3],
        intensity: 2.0,
        position: DVec3::ZERO,
        direction: Vec3::new(0.3, -0.5, -1.0).normalize(),
        range: None,
    });
    let mut opaque = scene.clone();
    for material in &mut opaque.materials {
        if material.alpha_mode == AlphaMode::Blend {
            material.alpha_mode = AlphaMode::Opaque;
        }
    }
    let gpu = gpu();
    let size = (128, 96);
    for pipeline in [
        "deferred_msaa_4x.ron",
        "deferred_msaa_4x_tiled.ron",
        "forward_msaa_4x.ron",
    ] {
        let render = |scene: &Scene| {
            let frame = Render::new(pipeline, &path, size)
                .with_scene(scene.clone())
                .features(SceneFeatures::of(scene).names())
                .run(&gpu);
            let passes: Vec<String> = frame.plan().passes.iter().map(|p| p.name.clone()).collect();
            (passes, frame.image(&gpu, "color"))
        };
        let (passes, with_blend) = render(&scene);
        assert!(
            passes.iter().any(|p| p == "transparent"),
            "{pipeline}: {passes:?}"
        );
        let (passes, all_opaque) = render(&opaque);
        assert!(
            !passes.iter().any(|p| p == "transparent"),
            "{pipeline}: {passes:?}"
        );
        let lit = with_blend
            .pixels
            .iter()
            .filter(|p| p[..3] != [0, 0, 0])
            .count();
        assert!(lit > 1000, "{pipeline}: only {lit} pixels lit");
        let differ = with_blend
            .pixels
            .iter()
            .zip(&all_opaque.pixels)
            .filter(|(a, b)| pixel_diff(**a, **b) > 8)
            .count();
        assert!(
            differ > 100,
            "{pipeline}: only {differ} pixels differ between BLEND and OPAQUE"
        );
        println!(
            "{pipeline}: {differ} of {} pixels differ from OPAQUE",
            size.0 * size.1
        );
    }
}

fn fixture_path() -> String {
    let path = fixture("AlphaBlendModeTest/AlphaBlendModeTest.glb");
    path.to_str().unwrap().to_owned()
}

/// Every pipeline that renders the lit scene declares `blend` and adds the transparent
/// passes for a scene with BLEND materials only: compiled for the built-in scenes'
/// features its plan is the one without them, which is the plan it had before they
/// existed. (No GPU: plans against the WebGPU defaults.)
#[test]
fn pipelines_add_the_transparent_passes_for_blend_scenes_only() {
    let file = panels_file(
        "blend_plans",
        &[
            Panel::background([0.0, 0.0, 1.0]),
            Panel::unlit(0.0, 0.5, [1.0, 0.0, 0.0, 0.5], true),
        ],
    );
    let blend = SceneFeatures::of(&load(&file)).names();
    let mut registry = Registry::with_builtins();
    rgraph_passes::register(&mut registry, None);
    let options = CompileOptions {
        output_size: SIZE,
        profile: DeviceProfile::webgpu(),
    };
    for (pipeline, _) in PIPELINES {
        let path = format!("{}/pipelines/{}", env!("CARGO_MANIFEST_DIR"), pipeline.name);
        let mut loaded = load_file(&path, &registry).unwrap_or_else(|e| panic!("{e}"));
        loaded.keep_outputs(&["color"]).expect("color is an output");
        let passes = |features: &Features| -> Vec<String> {
            let plan = loaded
                .compile_for(&options, features)
                .unwrap_or_else(|e| panic!("{pipeline}: {e}"));
            plan.passes.iter().map(|p| p.name.clone()).collect()
        };
        let with = passes(&blend);
        let at = |name: &str| with.iter().position(|p| p == name);
        let (Some(transparent), Some(composite), Some(tonemap)) = (
            at("transparent"),
            at("composite transparent"),
            at("tonemap"),
        ) else {
            panic!("{pipeline}: {with:?}");
        };
        assert!(
            transparent < composite && composite < tonemap,
            "{pipeline}: {with:?}"
        );
        for scene in [
            "builtin:spheres",
            "builtin:dense",
            "builtin:lights",
            "builtin:unlit",
        ] {
            let features = SceneFeatures::of(&Scene::load(scene).unwrap()).names();
            let without = passes(&features);
            assert!(
                without.iter().all(|p| !p.contains("transparent")),
                "{pipeline}, {scene}: {without:?}"
            );
        }
    }
}

/// `rgraph explain --scene` shows the transparent passes and their variant for a scene
/// with BLEND materials, and for a scene without them says the condition dropped them.
#[test]
fn explain_shows_the_transparent_passes_for_a_blend_scene_only() {
    let file = panels_file(
        "blend_explain",
        &[
            Panel::background([0.0, 0.0, 1.0]),
            Panel::unlit(0.0, 0.5, [1.0, 0.0, 0.0, 0.5], true),
        ],
    );
    let explain = |scene: &str| {
        crate::cli_support::rgraph(&[
            "explain",
            "--pipeline",
            "pipelines/deferred_msaa_4x_tiled.ron",
            "--scene",
            scene,
            "--size",
            "64x64",
        ])
        .expect(0)
        .stdout
    };
    let with = explain(&file);
    for shown in [
        "features: blend",
        ". transparent (render)",
        ". composite transparent (render)",
        "transparent.wgsl {",
    ] {
        assert!(with.contains(shown), "no {shown:?} in:\n{with}");
    }
    let without = explain("builtin:spheres");
    assert!(
        !without.contains(". transparent (render)"),
        "the transparent pass runs for builtin:spheres:\n{without}"
    );
    assert!(
        without.contains("condition \"blend\" is false"),
        "no reason for dropping the transparent passes in:\n{without}"
    );
}

/// Slots of the wrong kind are load errors naming the pass, the slot and the resource:
/// an accumulation of another size than the image it composites onto, of another format,
/// or of another sample count than the depth it is tested against.
#[test]
fn bad_transparent_slots_are_errors_naming_pass_slot_and_resource() {
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("pipelines/forward_msaa_4x.ron");
    let text = std::fs::read_to_string(&path).unwrap();
    let mut registry = Registry::with_builtins();
    rgraph_passes::register(&mut registry, None);
    let accum = r#""transparent": Texture(format: "rgba16float", samples: Param(name: "msaa", default: 4), when: "blend"),"#;
    for (from, to, expected) in [
        (
            accum,
            r#""transparent": Texture(format: "rgba16float", size: Relative(0.5), samples: Param(name: "msaa", default: 4), when: "blend"),"#,
            &[
                "pass \"composite transparent\"",
                "slot \"resolved\": \"blended_hdr\" is Relative(1.0), but the accumulation it \
                 composites (\"transparent\") is Relative(0.5)",
            ][..],
        ),
        (
            accum,
            r#""transparent": Texture(format: "rgba8unorm", samples: Param(name: "msaa", default: 4), when: "blend"),"#,
            &[
                "pass \"transparent\"",
                "slot \"accum\": \"transparent\" is rgba8unorm, but the transparent accumulation \
                 must be rgba16float",
            ][..],
        ),
        (
            accum,
            r#""transparent": Texture(format: "rgba16float", when: "blend"),"#,
            &[
                "pass \"transparent\"",
                "slot \"accum\": \"transparent\" has 1 sample(s), but the transparent \
                 accumulation must have 4",
            ][..],
        ),
    ] {
        assert!(text.contains(from), "no {from:?} to edit");
        let message = match load_str(&path, &text.replace(from, to), &registry) {
            Ok(_) => panic!("forward_msaa_4x.ron with {to:?} loaded"),
            Err(errors) => errors.to_string(),
        };
        for part in expected {
            assert!(message.contains(part), "no {part:?} in:\n{message}");
        }
    }
}

/// `rgraph render` warns when the scene has BLEND materials and the pipeline has no
/// `transparent` pass to draw them (the opaque passes skip them), and not otherwise.
#[test]
fn render_warns_when_the_pipeline_leaves_blend_meshes_out() {
    let file = panels_file(
        "blend_warning",
        &[
            Panel::background([0.0, 0.0, 1.0]),
            Panel::unlit(0.0, 0.5, [1.0, 0.0, 0.0, 0.5], true),
        ],
    );
    let dir = temp_dir("blend_warning_pipeline");
    let opaque_only = dir.join("forward_opaque_only.ron");
    std::fs::write(&opaque_only, FORWARD_OPAQUE_ONLY).unwrap();
    let warning = "warning: the scene has alpha BLEND materials, but";
    let out = dir.join("frame.png");
    let render = |pipeline: &str| render_stderr(pipeline, &file, (64, 64), &out);
    let stderr = render(opaque_only.to_str().unwrap());
    assert!(
        stderr.contains(warning) && stderr.contains("has no `transparent` pass"),
        "{stderr}"
    );
    let stderr = render("pipelines/forward_msaa_4x.ron");
    assert!(!stderr.contains(warning), "{stderr}");
}
