//! glTF points and lines end to end, from files the tests write: under an orthographic
//! camera 3 units in front whose view is 2.5 units across (so at 64x64 a unit is 25.6
//! pixels and pixel column `x` is centred at world x = (x + 0.5) / 25.6 - 1.25), in front
//! of an opaque unlit blue background quad that fills the view. Every pipeline that draws
//! a scene draws them after the opaque scene (`points_lines`), unlit, and composites them
//! by coverage (`composite_transparent`), compiled for the scene's features (they
//! include `points_lines`).

use serde_json::{json, Value};

use crate::cli_support::{render_stderr, FORWARD_OPAQUE_ONLY};
use crate::deferred_support::{gpu, PipelineFile, Render};
use crate::gltf_writer::{temp_dir, Gltf};
use rgraph_core::file::{load_file, Registry};
use rgraph_core::{CompileOptions, DeviceProfile, Features};
use rgraph_scene::analysis::Features as SceneFeatures;
use rgraph_scene::{Scene, Topology};

const SIZE: (u32, u32) = (64, 64);
/// Pixels per world unit.
const SCALE: f32 = 25.6;
const BLUE: [f32; 3] = [0.0, 0.0, 1.0];
const RED: [f32; 3] = [1.0, 0.0, 0.0];
const YELLOW: [f32; 3] = [1.0, 1.0, 0.0];
/// The point's colour: base colour (0.5, 0.5, 0.5) times COLOR_0 (0, 1, 0), plus
/// emission (0.25, 0, 0).
const POINT: [f32; 3] = [0.25, 0.5, 0.0];
/// The line's pixel row and the point's pixel.
const LINE_ROW: u32 = 20;
const POINT_AT: (u32, u32) = (44, 44);
/// The columns the occluding panel covers wholly on the line's row.
const OCCLUDED: std::ops::RangeInclusive<u32> = 7..=18;

/// Every pipeline file that draws a scene, as the transparency tests list them, with the
/// single-sampled HDR image it tone-maps: one sample per pixel and four, G-buffers,
/// forward, the light pre-pass and the visibility buffer's hardware and compute rasters.
const PIPELINES: [(PipelineFile, &str); 10] = [
    on_device("deferred_noaa.ron", "hdr_lit"),
    on_device("deferred_noaa_tiled.ron", "resolved"),
    on_device("deferred_gbuffer_resolve_4x.ron", "hdr_lit"),
    on_device("deferred_msaa_4x.ron", "resolved"),
    on_device("deferred_msaa_4x_tiled.ron", "resolved"),
    on_device("deferred_msaa_4x_lean.ron", "resolved"),
    on_device("forward_msaa_4x.ron", "resolved"),
    on_device("light_prepass_msaa_4x.ron", "resolved"),
    on_device("visibility_msaa_4x.ron", "resolved"),
    (
        PipelineFile::gpu_branch("visibility_msaa_4x.ron"),
        "resolved",
    ),
];

const fn on_device(
    name: &'static str,
    image: &'static str,
) -> (PipelineFile<'static>, &'static str) {
    (PipelineFile::for_device(name), image)
}

/// World x or y of pixel column or row `pixel`'s centre (y grows up, rows down).
fn world_x(pixel: u32) -> f32 {
    (pixel as f32 + 0.5) / SCALE - 1.25
}

fn world_y(pixel: u32) -> f32 {
    1.25 - (pixel as f32 + 0.5) / SCALE
}

/// An unlit opaque square of half-side `half` centred at `center`, facing +z.
fn panel(gltf: &mut Gltf, center: [f32; 3], half: f32, color: [f32; 3]) {
    let h = half;
    let positions = gltf.floats(&[[-h, -h, 0.0], [h, -h, 0.0], [h, h, 0.0], [-h, h, 0.0]]);
    let indices = gltf.indices_u16(&[0, 1, 2, 0, 2, 3]);
    let material = gltf.push(
        "materials",
        json!({ "pbrMetallicRoughness": { "baseColorFactor": [color[0], color[1], color[2], 1.0] },
                "extensions": { "KHR_materials_unlit": {} } }),
    );
    let mesh = gltf.push(
        "meshes",
        json!({ "primitives": [{ "attributes": { "POSITION": positions },
                                 "indices": indices, "material": material }] }),
    );
    gltf.root(json!({ "mesh": mesh, "translation": center }));
}

/// A primitive of `mode` over `positions` (with COLOR_0 `colors` where given) and
/// `material`, in a mesh of its own placed at the origin.
fn strokes(
    gltf: &mut Gltf,
    mode: u32,
    positions: &[[f32; 3]],
    colors: Option<&[[f32; 3]]>,
    material: Value,
) {
    let positions = gltf.floats(positions);
    let mut attributes = json!({ "POSITION": positions });
    if let Some(colors) = colors {
        attributes["COLOR_0"] = json!(gltf.floats(colors));
    }
    let material = gltf.push("materials", material);
    let mesh = gltf.push(
        "meshes",
        json!({ "name": "strokes", "primitives": [{ "attributes": attributes, "mode": mode,
                                                    "material": material }] }),
    );
    gltf.root(json!({ "mesh": mesh }));
}

/// The camera and, with `background`, the blue quad filling the view.
fn view(gltf: &mut Gltf, background: bool) {
    gltf.json["extensionsUsed"] = json!(["KHR_materials_unlit"]);
    if background {
        panel(gltf, [0.0, 0.0, -1.0], 2.0, BLUE);
    }
    let camera = gltf.push(
        "cameras",
        json!({ "type": "orthographic",
                "orthographic": { "xmag": 1.25, "ymag": 1.25, "znear": 0.1, "zfar": 10.0 } }),
    );
    gltf.root(json!({ "camera": camera, "translation": [0.0, 0.0, 3.0] }));
}

/// The analytic scene: a red line across the view through the centres of row
/// [`LINE_ROW`] (LINE_STRIP of three vertices), a point at [`POINT_AT`]'s centre, a
/// yellow opaque panel in front of the line's columns 7 to 18 (x from -1 to -0.5) and of
/// a second point behind it, all over the blue background; written as `test`/scene.gltf.
fn analytic_file(test: &str) -> String {
    let mut gltf = Gltf::default();
    view(&mut gltf, true);
    panel(&mut gltf, [-0.75, world_y(LINE_ROW), 0.5], 0.25, YELLOW);
    let y = world_y(LINE_ROW);
    strokes(
        &mut gltf,
        3,
        &[[-2.0, y, 0.0], [0.0, y, 0.0], [2.0, y, 0.0]],
        None,
        json!({ "pbrMetallicRoughness": { "baseColorFactor": [1.0, 0.0, 0.0, 1.0] } }),
    );
    let (px, py) = POINT_AT;
    strokes(
        &mut gltf,
        0,
        &[
            [world_x(px), world_y(py), 0.0],
            [-0.75, world_y(LINE_ROW) + 0.1, 0.0],
        ],
        Some(&[[0.0, 1.0, 0.0], [0.0, 1.0, 0.0]]),
        json!({ "pbrMetallicRoughness": { "baseColorFactor": [0.5, 0.5, 0.5, 1.0] },
                "emissiveFactor": [0.25, 0.0, 0.0] }),
    );
    let path = temp_dir(test).join("scene.gltf");
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
    let gpu = gpu();
    let export = format!("outputs: [\"{image}\", \"color\"");
    Render::new(pipeline, file, SIZE)
        .with_scene(scene.clone())
        .features(SceneFeatures::of(scene).names())
        .edit("outputs: [\"color\"", &export)
        .run(&gpu)
        .hdr(&gpu, image)
}

fn rgb(hdr: &[[f32; 4]], x: u32, y: u32) -> [f32; 3] {
    let p = hdr[(y * SIZE.0 + x) as usize];
    [p[0], p[1], p[2]]
}

/// What the analytic scene shows at pixel (x, y), where a pixel is covered wholly or
/// not at all; `None` on the occluding panel's edge columns, which 4x MSAA mixes.
fn expected(x: u32, y: u32) -> Option<[f32; 3]> {
    let (px, py) = POINT_AT;
    let on_panel_row = (14..=26).contains(&y);
    if on_panel_row && (x == 6 || x == 19) || (y == 14 || y == 26) && (6..=19).contains(&x) {
        return None;
    }
    if on_panel_row && OCCLUDED.contains(&x) {
        return Some(YELLOW);
    }
    if y == LINE_ROW {
        return Some(RED);
    }
    if px.abs_diff(x) <= 1 && py.abs_diff(y) <= 1 {
        return Some(POINT);
    }
    Some(BLUE)
}

/// A line across the view covers exactly its pixel row, a point of the default 3 pixels
/// exactly its 3 x 3 pixels, each in its unlit colour (base colour times COLOR_0 plus
/// emission) exactly, and an opaque panel in front hides them; in every pipeline, with
/// one sample per pixel and with four (the pixels are wholly covered or not at all, so
/// MSAA changes none of them).
#[test]
fn points_and_lines_cover_their_pixels_in_every_pipeline() {
    let file = analytic_file("points_lines_analytic");
    let scene = load(&file);
    assert!(SceneFeatures::of(&scene).points_lines);
    for (pipeline, image) in PIPELINES {
        let hdr = hdr(pipeline, image, &file, &scene);
        let mut wrong = Vec::new();
        for y in 0..SIZE.1 {
            for x in 0..SIZE.0 {
                let got = rgb(&hdr, x, y);
                if let Some(want) = expected(x, y) {
                    if got != want {
                        wrong.push(((x, y), got, want));
                    }
                }
            }
        }
        assert!(
            wrong.is_empty(),
            "{pipeline}: {} pixels differ, first (pixel, got, want): {:?}",
            wrong.len(),
            &wrong[..wrong.len().min(8)]
        );
    }
}

/// A red line across the view and a point (as in the analytic scene), each placed by a
/// node of its own that animation "drift" moves (LINEAR, keys at 0 and 2 s): the line's
/// node down from row 10's centre to row 70's, the point's node right from column 10's
/// to column 50's, on row [`POINT_AT`]'s. At rest they are on row 5 and column 5.
fn drifting_file(test: &str) -> String {
    let mut gltf = Gltf::default();
    view(&mut gltf, true);
    let line = json!({ "pbrMetallicRoughness": { "baseColorFactor": [1.0, 0.0, 0.0, 1.0] } });
    strokes(
        &mut gltf,
        1,
        &[[-2.0, 0.0, 0.0], [2.0, 0.0, 0.0]],
        None,
        line,
    );
    let point = json!({ "pbrMetallicRoughness": { "baseColorFactor": [0.5, 0.5, 0.5, 1.0] },
                        "emissiveFactor": [0.25, 0.0, 0.0] });
    strokes(&mut gltf, 0, &[[0.0; 3]], Some(&[[0.0, 1.0, 0.0]]), point);
    // `view` placed the background and the camera as nodes 0 and 1.
    let (line_node, point_node) = (2, 3);
    let y = world_y(POINT_AT.1);
    gltf.json["nodes"][line_node]["translation"] = json!([0.0, world_y(5), 0.0]);
    gltf.json["nodes"][point_node]["translation"] = json!([world_x(5), y, 0.0]);
    let times = gltf.floats(&[[0.0], [2.0]]);
    let down = gltf.floats(&[[0.0, world_y(10), 0.0], [0.0, world_y(70), 0.0]]);
    let right = gltf.floats(&[[world_x(10), y, 0.0], [world_x(50), y, 0.0]]);
    let channel = |sampler, node| json!({ "sampler": sampler, "target": { "node": node, "path": "translation" } });
    let sampler = |output| json!({ "input": times, "output": output, "interpolation": "LINEAR" });
    gltf.push(
        "animations",
        json!({ "name": "drift",
                "channels": [channel(0, line_node), channel(1, point_node)],
                "samplers": [sampler(down), sampler(right)] }),
    );
    let path = temp_dir(test).join("scene.gltf");
    gltf.write_embedded(&path);
    path.to_str().unwrap().to_owned()
}

/// Points and lines move with their animated nodes: at 0.5, 1 and 1.5 s of "drift" (set
/// as the frame inputs' pose, frame after frame) the line covers exactly row 10 + 30 t
/// (25, 40, 55) and the point exactly the 3 x 3 pixels around column 10 + 20 t (20, 30,
/// 40), each in its colour, everything else the blue background, in every pipeline. The
/// last line lies below the rectangle the rest pose covers, which the composite would
/// clip it to if that rectangle did not follow the pose.
#[test]
fn animated_points_and_lines_are_where_the_pose_puts_them() {
    let file = drifting_file("points_lines_animated");
    let scene = load(&file);
    let id = scene.find_animation("drift").expect("the animation");
    let features = SceneFeatures::of(&scene).names();
    for (pipeline, image) in PIPELINES {
        let gpu = gpu();
        let export = format!("outputs: [\"{image}\", \"color\"");
        let mut frame = Render::new(pipeline, &file, SIZE)
            .with_scene(scene.clone())
            .features(features.clone())
            .edit("outputs: [\"color\"", &export)
            .run(&gpu);
        for time in [0.5, 1.0, 1.5] {
            let mut inputs = frame.inputs();
            inputs.set_pose(scene.animated_pose(id, time));
            frame.next(inputs);
            let hdr = frame.hdr(&gpu, image);
            let (row, column) = ((10.0 + 30.0 * time) as u32, (10.0 + 20.0 * time) as u32);
            let expected = |x: u32, y: u32| match () {
                _ if column.abs_diff(x) <= 1 && POINT_AT.1.abs_diff(y) <= 1 => POINT,
                _ if y == row => RED,
                _ => BLUE,
            };
            let wrong: Vec<_> = (0..SIZE.1)
                .flat_map(|y| (0..SIZE.0).map(move |x| (x, y)))
                .filter(|&(x, y)| rgb(&hdr, x, y) != expected(x, y))
                .map(|(x, y)| ((x, y), rgb(&hdr, x, y), expected(x, y)))
                .collect();
            assert!(
                wrong.is_empty(),
                "{pipeline} at {time} s: {} pixels differ, first (pixel, got, want): {:?}",
                wrong.len(),
                &wrong[..wrong.len().min(8)]
            );
        }
    }
}

/// Frame inputs without one finite transform per points-and-lines primitive are refused,
/// naming what is wrong.
#[test]
fn points_lines_transforms_that_do_not_fit_the_scene_are_refused() {
    use rgraph_passes::{FrameInputs, FrameInputsError, Host, Overrides};
    let file = drifting_file("points_lines_refused");
    let scene = std::sync::Arc::new(load(&file));
    let host = Host::new(scene.clone(), Overrides::default());
    let mut inputs = FrameInputs::of(&scene);
    inputs.points_lines.pop();
    assert_eq!(
        host.set_frame(inputs).unwrap_err().to_string(),
        format!("frame inputs give 1 points-and-lines transforms, but scene \"{file}\" has 2")
    );
    let mut inputs = FrameInputs::of(&scene);
    inputs.points_lines[1].w_axis.y = f64::INFINITY;
    assert_eq!(
        host.set_frame(inputs).unwrap_err(),
        FrameInputsError::NotFinite {
            scene: file.clone(),
            what: "the transform of points and lines \"mesh 2 \"strokes\" primitive 0\"".to_owned(),
        }
    );
}

/// MSAA anti-aliases lines: a horizontal line whose centre lies a quarter pixel below
/// row 30's centre covers, with 4x MSAA's standard sample positions (one sample in each
/// quarter of a pixel's height), three of row 30's samples and one of row 31's, so the
/// rows are 3/4 and 1/4 red over the blue (within an 8-bit step); with one sample per
/// pixel a row is red or blue, and exactly one row is red.
#[test]
fn msaa_antialiases_lines() {
    let mut gltf = Gltf::default();
    view(&mut gltf, true);
    let y = world_y(30) - 0.25 / SCALE;
    strokes(
        &mut gltf,
        1,
        &[[-2.0, y, 0.0], [2.0, y, 0.0]],
        None,
        json!({ "pbrMetallicRoughness": { "baseColorFactor": [1.0, 0.0, 0.0, 1.0] } }),
    );
    let path = temp_dir("points_lines_msaa").join("scene.gltf");
    gltf.write_embedded(&path);
    let file = path.to_str().unwrap();
    let scene = load(file);
    let step = 1.0 / 255.0;
    for (pipeline, image) in PIPELINES {
        let hdr = hdr(pipeline, image, file, &scene);
        let samples = if pipeline.name.contains("noaa") { 1 } else { 4 };
        for x in 0..SIZE.0 {
            let red = |y| rgb(&hdr, x, y)[0];
            let (upper, lower) = (red(30), red(31));
            for y in [29, 32] {
                assert_eq!(rgb(&hdr, x, y), BLUE, "{pipeline}: ({x}, {y})");
            }
            match samples {
                1 => assert!(
                    [upper, lower] == [1.0, 0.0] || [upper, lower] == [0.0, 1.0],
                    "{pipeline}: column {x} is {upper} and {lower} red"
                ),
                _ => assert!(
                    (upper - 0.75).abs() <= step && (lower - 0.25).abs() <= step,
                    "{pipeline}: column {x} is {upper} and {lower} red"
                ),
            }
        }
    }
}

/// A file mixing triangles and lines (tests/fixtures/points_lines/mixed.gltf: a green
/// quad and a red LINE_LOOP outline) draws both: the quad's pixels green, and each row
/// the outline's left side crosses one pixel's worth of red (within an 8-bit step),
/// whether one pixel holds it all or 4x MSAA spreads it.
#[test]
fn a_file_of_triangles_and_lines_draws_both() {
    let file = format!(
        "{}/tests/fixtures/points_lines/mixed.gltf",
        env!("CARGO_MANIFEST_DIR")
    );
    let scene = load(&file);
    assert_eq!((scene.meshes.len(), scene.points_lines.len()), (1, 1));
    assert_eq!(scene.points_lines[0].topology, Topology::Lines);
    assert_eq!(scene.points_lines[0].indices, [0, 1, 1, 2, 2, 3, 3, 0]);
    for (pipeline, image) in PIPELINES {
        let hdr = hdr(pipeline, image, &file, &scene);
        assert_eq!(rgb(&hdr, 20, 32), [0.0, 1.0, 0.0], "{pipeline}: the quad");
        // The left side at x = 0.25, pixel column 38.4, from row 19.2 to 44.8.
        for y in 22..=42 {
            let red: f32 = (35..=41).map(|x| rgb(&hdr, x, y)[0]).sum();
            assert!(
                (red - 1.0).abs() <= 1.0 / 255.0,
                "{pipeline}: row {y} holds {red} pixels of red"
            );
        }
        assert_eq!(rgb(&hdr, 48, 32)[0], 0.0, "{pipeline}: inside the outline");
    }
}

/// Every pipeline that draws a scene adds `points lines` and `composite points lines`
/// (after the transparent composite, before tone mapping) for a scene with points or
/// lines only: compiled for the built-in scenes' features its plan is the one without
/// them. (No GPU: plans against the WebGPU defaults.)
#[test]
fn pipelines_add_the_points_lines_passes_for_such_scenes_only() {
    let file = analytic_file("points_lines_plans");
    let with_points = SceneFeatures::of(&load(&file)).names();
    let mut registry = Registry::with_builtins();
    rgraph_passes::register(&mut registry, None);
    let options = CompileOptions {
        output_size: SIZE,
        profile: DeviceProfile::webgpu(),
    };
    let files = [
        "deferred_gbuffer_resolve_4x.ron",
        "deferred_msaa_4x.ron",
        "deferred_msaa_4x_adaptive.ron",
        "deferred_msaa_4x_lean.ron",
        "deferred_msaa_4x_ssao.ron",
        "deferred_msaa_4x_tiled.ron",
        "deferred_noaa.ron",
        "deferred_noaa_fxaa.ron",
        "deferred_onthefly_resolve_4x.ron",
        "deferred_per_sample_4x.ron",
        "forward_msaa_4x.ron",
        "light_prepass_msaa_4x.ron",
        "msaa_4x_taa.ron",
        "particles_full_res.ron",
        "particles_low_res.ron",
        "particles_mixed_res.ron",
        "reference_ssaa16.ron",
        "taa.ron",
        "visibility_msaa_4x.ron",
        "visibility_noaa.ron",
    ];
    for pipeline in files {
        let path = format!("{}/pipelines/{pipeline}", env!("CARGO_MANIFEST_DIR"));
        let mut loaded = load_file(&path, &registry).unwrap_or_else(|e| panic!("{e}"));
        loaded.keep_outputs(&["color"]).expect("color is an output");
        let passes = |features: &Features| -> Vec<String> {
            let plan = loaded
                .compile_for(&options, features)
                .unwrap_or_else(|e| panic!("{pipeline}: {e}"));
            plan.passes.iter().map(|p| p.name.clone()).collect()
        };
        let with = passes(&with_points);
        let at = |name: &str| with.iter().position(|p| p.starts_with(name));
        let (Some(draw), Some(composite), Some(tonemap)) = (
            at("points lines"),
            at("composite points lines"),
            at("tonemap"),
        ) else {
            panic!("{pipeline}: {with:?}");
        };
        assert!(
            draw < composite && composite < tonemap,
            "{pipeline}: {with:?}"
        );
        for scene in ["builtin:spheres", "builtin:dense", "builtin:unlit"] {
            let features = SceneFeatures::of(&Scene::load(scene).unwrap()).names();
            let without = passes(&features);
            assert!(
                without.iter().all(|p| !p.contains("points lines")),
                "{pipeline}, {scene}: {without:?}"
            );
        }
    }
}

/// `rgraph render` says when the pipeline cannot draw the scene's points and lines (a
/// forward pipeline without the `points_lines` pass leaves them out), and stays quiet
/// with a pipeline that draws them.
#[test]
fn render_warns_when_the_pipeline_leaves_the_scenes_lines_out() {
    let dir = temp_dir("points_lines_warning");
    let without = dir.join("forward_without_points_lines.ron");
    std::fs::write(&without, FORWARD_OPAQUE_ONLY).unwrap();
    let out = dir.join("frame.png");
    let scene = "tests/fixtures/points_lines/mixed.gltf";
    let render = |pipeline: &str| render_stderr(pipeline, scene, (32, 32), &out);
    let stderr = render(without.to_str().unwrap());
    assert!(
        stderr.contains("warning: the scene has 4 line segments, but")
            && stderr.contains("has no `points_lines` pass to draw them"),
        "{stderr}"
    );
    let stderr = render("pipelines/forward_msaa_4x.ron");
    assert!(!stderr.contains("line segments, but"), "{stderr}");
}
