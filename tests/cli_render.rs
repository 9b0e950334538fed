//! `rgraph render` as a user runs it: the built binary on lavapipe (unless RGRAPH_ADAPTER
//! says otherwise), checked by exit status, stdout, stderr and the PNG's pixels. A machine
//! without a Vulkan adapter fails the rendering tests with the binary's own explanation.

use crate::cli_support;

use std::path::{Path, PathBuf};

use cli_support::{rgraph, Run};
use tempfile::TempDir;

/// The generic stand-in for the deferred pipelines: "color" is a vertical gradient from
/// red to blue, "debug.edges" solid green.
const FIXTURE: &str = "tests/fixtures/render_generic.ron";

fn render(args: &[&str]) -> Run {
    rgraph(&[&["render"], args].concat())
}

/// `--pipeline FIXTURE --out OUT`, then `extra`, then 64x48 unless `extra` sets a size.
fn render_fixture(out: &Path, extra: &[&str]) -> Run {
    let out = out.to_str().expect("temp paths are UTF-8");
    let mut args = vec!["--pipeline", FIXTURE, "--out", out];
    args.extend_from_slice(extra);
    for (flag, value) in [("--width", "64"), ("--height", "48")] {
        if !extra.contains(&flag) {
            args.extend([flag, value]);
        }
    }
    render(&args)
}

fn temp_dir() -> TempDir {
    tempfile::tempdir().expect("a temporary directory")
}

/// After a failure the directory holds nothing: no PNG, no partial file.
fn assert_nothing_written(dir: &TempDir) {
    let left: Vec<PathBuf> = std::fs::read_dir(dir.path())
        .expect("readable temp dir")
        .map(|e| e.expect("dir entry").path())
        .collect();
    assert!(left.is_empty(), "a failed render left files: {left:?}");
}

/// The defaults (pipelines/visibility_msaa_4x.ron on builtin:spheres) at 64x48, plus
/// `extra`.
fn render_default(out: &Path, extra: &[&str]) -> Run {
    let out = out.to_str().expect("temp paths are UTF-8");
    let mut args = vec!["--width", "64", "--height", "48", "--out", out];
    args.extend_from_slice(extra);
    render(&args)
}

/// pipelines/deferred_msaa_4x_tiled.ron, a G-buffer with its debug views and scene
/// conditions, on builtin:spheres at 64x48, plus `extra`.
fn render_tiled(out: &Path, extra: &[&str]) -> Run {
    let pipeline = ["--pipeline", "pipelines/deferred_msaa_4x_tiled.ron"];
    render_default(out, &[&pipeline[..], extra].concat())
}

/// How many different colors an image has: a real render of a scene has many.
fn distinct_colors(image: &image::RgbaImage) -> usize {
    let mut colors: Vec<[u8; 4]> = image.pixels().map(|p| p.0).collect();
    colors.sort_unstable();
    colors.dedup();
    colors.len()
}

/// Mean of the RGB channels over the image, 0 to 255.
fn mean_brightness(image: &image::RgbaImage) -> f64 {
    let sum: u64 = image
        .pixels()
        .map(|p| p.0[..3].iter().map(|&c| c as u64).sum::<u64>())
        .sum();
    sum as f64 / (3 * image.pixels().len()) as f64
}

fn read_png(path: &Path) -> image::RgbaImage {
    image::open(path)
        .unwrap_or_else(|e| panic!("{} is not a readable PNG: {e}", path.display()))
        .into_rgba8()
}

#[test]
fn renders_the_final_view_as_an_srgb_png() {
    let dir = temp_dir();
    let out = dir.path().join("frame.png");
    let run = render_fixture(&out, &[]).expect(0);
    assert_eq!(
        run.stdout,
        format!("{}\n", out.display()),
        "stdout: the path only"
    );
    let image = read_png(&out);
    assert_eq!(image.dimensions(), (64, 48));
    // Row centres sit 1/96 from the ends of the gradient: nearly pure red at the top,
    // nearly pure blue at the bottom, sRGB-encoded, opaque.
    let top = image.get_pixel(10, 0).0;
    let bottom = image.get_pixel(50, 47).0;
    assert!(
        top[0] >= 250 && top[1] == 0 && top[2] <= 30 && top[3] == 255,
        "{top:?}"
    );
    assert!(
        bottom[0] <= 30 && bottom[1] == 0 && bottom[2] >= 250,
        "{bottom:?}"
    );
    // Halfway is linear 0.5 of each, which sRGB encodes as 188 (not 128).
    let middle = image.get_pixel(32, 24).0;
    assert!((180..=192).contains(&middle[0]), "{middle:?}");
    // The stages and the timing table, with the debug pass culled.
    run.stderr_has("load scene builtin:spheres")
        .stderr_has("write ")
        .stderr_has("GPU ms")
        .stderr_has("\nsky ")
        .stderr_has("\ntotal ")
        .stderr_has("logical")
        .stderr_has("culled: edges");
}

#[test]
fn a_debug_view_runs_only_its_passes() {
    let dir = temp_dir();
    let out = dir.path().join("edges.png");
    let run = render_fixture(&out, &["--view", "edges"]).expect(0);
    let image = read_png(&out);
    assert_eq!(image.dimensions(), (64, 48));
    assert!(
        image.pixels().all(|p| p.0 == [0, 255, 0, 255]),
        "solid green expected"
    );
    run.stderr_has("\nedges ").stderr_has("culled: sky");
}

/// A debug view of a TAA pipeline culls the TAA pass, and the history only it reads
/// with it: the history's textures once stayed in the plan without usages, which the
/// device refused ("Invalid usage flags").
#[test]
fn a_debug_view_of_a_taa_pipeline_drops_its_history() {
    let dir = temp_dir();
    for pipeline in ["pipelines/taa.ron", "pipelines/msaa_4x_taa.ron"] {
        let out = dir.path().join("motion.png");
        let out_arg = out.to_str().expect("temp paths are UTF-8");
        let args = [
            "render",
            "--pipeline",
            pipeline,
            "--view",
            "motion",
            "--out",
            out_arg,
        ];
        let run = rgraph(&[&args[..], &["--width", "64", "--height", "36"]].concat()).expect(0);
        assert_eq!(read_png(&out).dimensions(), (64, 36), "{pipeline}");
        let culled = run
            .stderr
            .lines()
            .find(|l| l.contains("culled:"))
            .unwrap_or_default();
        assert!(
            culled.contains("taa"),
            "{pipeline}: the TAA pass is not culled:\n{}",
            run.stderr
        );
    }
}

#[test]
fn a_view_the_pipeline_lacks_lists_the_views_it_has() {
    let dir = temp_dir();
    render_fixture(&dir.path().join("a.png"), &["--view", "albedo"])
        .expect(1)
        .stderr_has("--view albedo")
        .stderr_has("no output \"debug.albedo\"")
        .stderr_has("its views: final, edges");
    assert_nothing_written(&dir);
}

#[test]
fn sizes_must_be_at_least_one_pixel() {
    let dir = temp_dir();
    let out = dir.path().join("a.png");
    for flag in ["--width", "--height"] {
        render_fixture(&out, &[flag, "0"])
            .expect(2)
            .stderr_has(flag)
            .stderr_has("at least 1");
    }
    assert_nothing_written(&dir);
}

#[test]
fn sizes_above_the_device_limit_fail_before_rendering() {
    let dir = temp_dir();
    render_fixture(&dir.path().join("a.png"), &["--height", "1000000"])
        .expect(2)
        .stderr_has("--height 1000000 is above")
        .stderr_has("largest 2D texture");
    assert_nothing_written(&dir);
}

#[test]
fn exposure_must_be_finite_and_positive() {
    let dir = temp_dir();
    for exposure in ["0", "-1", "nan", "inf", "bright"] {
        render_fixture(&dir.path().join("a.png"), &["--exposure", exposure])
            .expect(2)
            .stderr_has("--exposure");
    }
    assert_nothing_written(&dir);
}

#[test]
fn tonemap_and_exposure_are_accepted_by_any_pipeline() {
    let dir = temp_dir();
    let out = dir.path().join("a.png");
    render_fixture(&out, &["--tonemap", "aces", "--exposure", "1.5"]).expect(0);
    assert_eq!(read_png(&out).dimensions(), (64, 48));
}

#[test]
fn an_unreadable_pipeline_is_a_usage_error_naming_it() {
    let dir = temp_dir();
    let out = dir.path().join("a.png");
    let out = out.to_str().unwrap();
    render(&["--pipeline", "pipelines/no_such.ron", "--out", out])
        .expect(2)
        .stderr_has("pipelines/no_such.ron")
        .stderr_has("cannot read");
    assert_nothing_written(&dir);
}

#[test]
fn an_invalid_pipeline_reports_file_line_and_column() {
    let dir = temp_dir();
    let pipeline = dir.path().join("bad.ron");
    std::fs::write(
        &pipeline,
        "Graph(\n  resources: { \"color\": Texture(format: \"rgba8unorm-srgb\") },\n  passes: [\n    (name: \"p\", plugin: \"no_such_plugin\", outputs: { \"color\": \"color\" }),\n  ],\n  outputs: [\"color\"],\n)\n",
    )
    .unwrap();
    let out = dir.path().join("a.png");
    render(&[
        "--pipeline",
        pipeline.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ])
    .expect(1)
    .stderr_has(&format!("{}:4:", pipeline.display()))
    .stderr_has("error: pass \"p\" uses plugin \"no_such_plugin\"");
    assert!(!out.exists());
}

#[test]
fn scene_errors_are_reported_with_their_source() {
    let dir = temp_dir();
    let gltf = dir.path().join("broken.gltf");
    std::fs::write(&gltf, "{ this is not glTF").unwrap();
    let out = dir.path().join("a.png");
    render_fixture(&out, &["--scene", gltf.to_str().unwrap()])
        .expect(1)
        .stderr_has(&format!("{}: not a valid glTF 2.0 file", gltf.display()));
    render_fixture(&out, &["--scene", "builtin:no_such_scene"])
        .expect(1)
        .stderr_has("unknown built-in scene `no_such_scene`");
    render_fixture(&out, &["--scene", "no/such/file.glb"])
        .expect(2)
        .stderr_has("no/such/file.glb");
    assert!(!out.exists());
}

#[test]
fn the_output_must_be_a_png_in_an_existing_directory() {
    let dir = temp_dir();
    render_fixture(&dir.path().join("missing").join("a.png"), &[])
        .expect(2)
        .stderr_has("does not exist");
    render_fixture(&dir.path().join("a.jpg"), &[])
        .expect(2)
        .stderr_has("must be a .png file");
    assert_nothing_written(&dir);
}

#[test]
fn an_over_dispatch_is_refused_before_the_device_and_keeps_the_old_file() {
    let dir = temp_dir();
    let out = dir.path().join("a.png");
    std::fs::write(&out, b"the previous frame").unwrap();
    let out_arg = out.to_str().unwrap();
    render(&[
        "--pipeline",
        "tests/fixtures/render_overdispatch.ron",
        "--width",
        "64",
        "--height",
        "48",
        "--out",
        out_arg,
    ])
    .expect(1)
    .stderr_has(
        "tests/fixtures/render_overdispatch.ron:12:21: error: pass \"overdispatch\" (compute): \
         dispatch Workgroups(1000000, 1, 1) has 1000000 in x: each count must be from 1 to 65535",
    );
    assert_eq!(std::fs::read(&out).unwrap(), b"the previous frame");
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
}

#[test]
fn help_teaches_defaults_and_examples() {
    let help = render(&["--help"]).expect(0).stdout;
    for text in [
        "pipelines/deferred_msaa_4x.ron",
        "builtin:spheres",
        "[default: 1280]",
        "[default: 720]",
        "[default: final]",
        "Examples:",
        "--no-specialise",
    ] {
        assert!(help.contains(text), "help lacks {text:?}:\n{help}");
    }
}

#[test]
fn a_pipeline_importing_engine_textures_is_refused_before_rendering() {
    let dir = temp_dir();
    render(&[
        "--pipeline",
        "tests/fixtures/render_import.ron",
        "--out",
        dir.path().join("a.png").to_str().unwrap(),
    ])
    .expect(1)
    .stderr_has("imports \"engine\", which an engine binds");
    assert_nothing_written(&dir);
}

#[test]
fn an_adapter_that_does_not_exist_is_a_usage_error_listing_the_others() {
    let dir = temp_dir();
    render_fixture(
        &dir.path().join("a.png"),
        &["--adapter", "no such adapter 9000"],
    )
    .expect(2)
    .stderr_has("no Vulkan adapter matches \"no such adapter 9000\"")
    .stderr_has("available:");
    assert_nothing_written(&dir);
}

/// The default pipeline is the visibility buffer, by the hardware raster on lavapipe.
#[test]
fn the_defaults_render_the_spheres_through_the_visibility_buffer() {
    let dir = temp_dir();
    let out = dir.path().join("frame.png");
    let run = render_default(&out, &[]).expect(0);
    let image = read_png(&out);
    assert_eq!(image.dimensions(), (64, 48));
    let colors = distinct_colors(&image);
    assert!(colors > 100, "a lit scene has many colors, got {colors}");
    // Its sun casts the spheres' shadows: the shadow maps, and the tiled pass reading them.
    run.stderr_has("\nshadow maps ")
        .stderr_has("\nvisibility (hardware raster) ")
        .stderr_has("\nlight tiled (hardware raster) ")
        .stderr_has("\ntonemap (cpu device) ")
        .stderr_has("culled: debug edges (hardware raster), debug fragments (hardware raster)");
}

#[test]
fn every_debug_view_of_the_tiled_pipeline_renders_without_the_lighting() {
    let dir = temp_dir();
    let views = [
        "edges",
        "albedo",
        "normals",
        "depth",
        "lights",
        "tile_lights",
    ];
    for view in views {
        let out = dir.path().join(format!("{view}.png"));
        let run = render_tiled(&out, &["--view", view]).expect(0);
        let image = read_png(&out);
        assert_eq!(image.dimensions(), (64, 48), "--view {view}");
        assert!(
            distinct_colors(&image) > 1,
            "--view {view} is one flat color"
        );
        run.stderr_has(&format!("\ndebug {} ", view.replace('_', " ")))
            .stderr_has("tonemap");
        assert!(
            !run.stderr.contains("\ntonemap "),
            "--view {view} ran the tone mapping:\n{}",
            run.stderr
        );
    }
}

#[test]
fn exposure_reaches_the_tone_mapping() {
    let dir = temp_dir();
    let dark = dir.path().join("dark.png");
    let bright = dir.path().join("bright.png");
    render_default(&dark, &["--tonemap", "reinhard", "--exposure", "0.25"]).expect(0);
    render_default(&bright, &["--tonemap", "reinhard", "--exposure", "4"]).expect(0);
    let (dark, bright) = (
        mean_brightness(&read_png(&dark)),
        mean_brightness(&read_png(&bright)),
    );
    assert!(
        bright > dark + 20.0,
        "exposure 4 ({bright:.1}) vs 0.25 ({dark:.1})"
    );
}

/// builtin:unlit at 64x48 with the tiled pipeline, plus `extra`.
fn render_unlit(out: &Path, extra: &[&str]) -> Run {
    let mut args = vec!["--scene", "builtin:unlit"];
    args.extend_from_slice(extra);
    render_tiled(out, &args)
}

#[test]
fn an_unlit_scene_renders_with_the_specialised_plan_and_the_same_image() {
    let dir = temp_dir();
    let (special, general) = (dir.path().join("s.png"), dir.path().join("g.png"));
    render_unlit(&special, &[])
        .expect(0)
        .stderr_has("specialised to the scene's features: no_lights, shallow_depth, unlit_only")
        .stderr_has("\ngbuffer (unlit) ")
        .stderr_has(
            "dropped by conditions: gbuffer, shadow maps, light tiled, resolve (no lights), \
             background, transparent, composite transparent, points lines, composite points \
             lines, auto exposure, tonemap (auto exposure), debug edges, debug tile lights, debug normals, debug lights",
        );
    let run = render_unlit(&general, &["--no-specialise"]).expect(0);
    run.stderr_has("\nlight tiled ");
    assert!(
        !run.stderr.contains("specialised to"),
        "--no-specialise still specialised:\n{}",
        run.stderr
    );
    let (special, general) = (read_png(&special), read_png(&general));
    let worst = special
        .pixels()
        .zip(general.pixels())
        .flat_map(|(a, b)| (0..4).map(move |c| a.0[c].abs_diff(b.0[c])))
        .max()
        .unwrap();
    // As tests/specialise_unlit.rs states for the library: within 1/255.
    assert!(worst <= 1, "a channel differs by {worst}/255");
    assert!(distinct_colors(&special) > 2, "a blank frame");
}

#[test]
fn a_view_the_scene_does_not_need_is_refused_with_the_reason() {
    let dir = temp_dir();
    let out = dir.path().join("normals.png");
    render_unlit(&out, &["--view", "normals"])
        .expect(1)
        .stderr_has(
            "output \"debug.normals\" of pipelines/deferred_msaa_4x_tiled.ron is not made for this \
             scene: condition \"!unlit_only\" is false (features: color_bytes_64, no_lights, shallow_depth, \
             unlit_only); \
             --no-specialise",
        );
    assert_nothing_written(&dir);
    render_unlit(&out, &["--view", "normals", "--no-specialise"]).expect(0);
    assert_eq!(read_png(&out).dimensions(), (64, 48));
}

/// visibility_msaa_4x.ron takes its branch for CPU adapters on lavapipe, the hardware
/// raster, and the summary says the device decided it, specialised or not (unspecialised,
/// every scene feature is set, `untabled_textures` and `particles` too: the G-buffer
/// fallback with the particle passes, tone mapped as on a CPU).
#[test]
fn the_visibility_pipeline_rasterises_by_the_hardware_on_a_cpu_device() {
    let dir = temp_dir();
    let out = dir.path().join("v.png");
    let pipeline = ["--pipeline", "pipelines/visibility_msaa_4x.ron"];
    render_default(&out, &pipeline)
        .expect(0)
        .stderr_has("\nvisibility (hardware raster) ")
        .stderr_has("\ndevice conditions: color_bytes_64, cpu_device\n")
        .stderr_has(
            "dropped by conditions: shadow raster, shadow maps (alpha mask), shadow resolve, \
             visibility, visibility (blend), visibility (points lines), depth pyramid (first phase), visibility \
             (second phase), depth pyramid, light tiled, keys depth, keys depth (points lines), ",
        );
    render_default(&out, &[&pipeline[..], &["--no-specialise"]].concat())
        .expect(0)
        .stderr_has("\ngbuffer (untabled textures, emissive) ")
        .stderr_has("\nparticles (off screen) ")
        .stderr_has("\ntonemap (cpu device, particles) ")
        .stderr_has("\ndevice conditions: color_bytes_64, cpu_device\n");
}

#[test]
fn a_lit_scene_is_specialised_only_in_its_depth_format() {
    let dir = temp_dir();
    let run = render_tiled(&dir.path().join("f.png"), &[]).expect(0);
    // builtin:spheres uses lights and lit materials; its depth spans 309 near planes.
    run.stderr_has("specialised to the scene's features: shadows, shallow_depth (")
        .stderr_has(
            "dropped by conditions: gbuffer (unlit), resolve (unlit), resolve (no lights), \
             background, transparent, composite transparent, points lines, composite points \
             lines, auto exposure, tonemap (auto exposure)\n",
        );
}

#[test]
fn a_fixed_size_output_says_that_width_and_height_do_not_apply() {
    let dir = temp_dir();
    let text = std::fs::read_to_string(FIXTURE).unwrap().replace(
        "\"color\": Texture(format: \"rgba8unorm-srgb\"),",
        "\"color\": Texture(format: \"rgba8unorm-srgb\", size: Absolute(32, 16)),",
    );
    // Next to the fixture, so its relative shader path still resolves.
    let pipeline =
        Path::new("tests/fixtures").join(format!(".fixed_size_{}.ron", std::process::id()));
    std::fs::write(&pipeline, text).unwrap();
    let out = dir.path().join("a.png");
    let run = render(&[
        "--pipeline",
        pipeline.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--width",
        "64",
        "--height",
        "48",
    ]);
    let _ = std::fs::remove_file(&pipeline);
    run.expect(0).stderr_has(&format!(
        "warning: --width 64 --height 48 do not apply: {} gives \"color\" a fixed size of \
         32x16, which is what was written",
        pipeline.display()
    ));
    assert_eq!(read_png(&out).dimensions(), (32, 16));
}

#[cfg(target_os = "linux")]
#[test]
fn an_unwritable_output_is_refused_before_any_rendering() {
    // /sys refuses new files even to root, who ignores permission bits.
    let run = render_fixture(Path::new("/sys/rgraph-test.png"), &[]).expect(2);
    run.stderr_has("--out /sys/rgraph-test.png: cannot write in /sys: ");
    assert!(
        !run.stderr.contains("open device") && !run.stderr.contains("load scene"),
        "it rendered before checking --out:\n{}",
        run.stderr
    );
}

/// A glTF file with a `65537 x 1` base-color image, wider than any device's largest 2D
/// texture, on a triangle.
fn gltf_with_a_wide_texture(dir: &Path) -> PathBuf {
    let png = dir.join("wide.png");
    image::RgbaImage::from_pixel(65_537, 1, image::Rgba([255, 0, 0, 255]))
        .save(&png)
        .unwrap();
    let floats: Vec<u8> = [0f32, 0., 0., 1., 0., 0., 0., 1., 0., 0., 0., 1., 0., 0., 1.]
        .iter()
        .flat_map(|v| v.to_le_bytes())
        .collect();
    std::fs::write(dir.join("triangle.bin"), &floats).unwrap();
    let gltf = serde_json::json!({
        "asset": { "version": "2.0" }, "scene": 0, "scenes": [{ "nodes": [0] }],
        "nodes": [{ "mesh": 0 }],
        "meshes": [{ "primitives": [{ "attributes": { "POSITION": 0, "TEXCOORD_0": 1 }, "material": 0 }] }],
        "materials": [{ "name": "wide", "pbrMetallicRoughness": { "baseColorTexture": { "index": 0 } } }],
        "textures": [{ "source": 0 }], "images": [{ "uri": "wide.png" }],
        "buffers": [{ "byteLength": 60, "uri": "triangle.bin" }],
        "bufferViews": [
            { "buffer": 0, "byteOffset": 0, "byteLength": 36 },
            { "buffer": 0, "byteOffset": 36, "byteLength": 24 }
        ],
        "accessors": [
            { "bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
              "min": [0, 0, 0], "max": [1, 1, 0] },
            { "bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC2" }
        ]
    });
    let path = dir.join("wide.gltf");
    std::fs::write(&path, gltf.to_string()).unwrap();
    path
}

#[test]
fn a_scene_texture_larger_than_the_device_is_named_before_any_upload() {
    let dir = temp_dir();
    let gltf = gltf_with_a_wide_texture(dir.path());
    let out = dir.path().join("a.png");
    let run = render_default(&out, &["--scene", gltf.to_str().unwrap()]).expect(2);
    run.stderr_has(&format!(
        "{}: texture image 0 \"wide.png\" is 65537x1, larger than ",
        gltf.display()
    ));
    assert!(!run.stderr.contains("upload and render"), "{}", run.stderr);
    assert!(!out.exists());
}

#[test]
fn exposure_auto_meters_the_frame_and_a_blown_out_frame_warns() {
    let dir = temp_dir();
    let out = dir.path().join("a.png");
    let auto = render_default(&out, &["--exposure", "auto"]).expect(0);
    auto.stderr_has("auto exposure")
        .stderr_has("tonemap (auto exposure)");
    assert!(!auto.stderr.contains("saturated"), "{}", auto.stderr);
    render_default(&out, &["--exposure", "50"])
        .expect(0)
        .stderr_has("% of the lit pixels are saturated (a channel at 255): lower --exposure, or let --exposure auto meter the frame");
}

#[test]
fn exposure_auto_needs_a_pipeline_that_meters_after_resolving() {
    let dir = temp_dir();
    let out = dir.path().join("a.png");
    let pipeline = "pipelines/deferred_msaa_4x_tonemapped_resolve.ron";
    render_default(&out, &["--pipeline", pipeline, "--exposure", "auto"])
        .expect(1)
        .stderr_has("error: pass \"resolve\" (resolve): auto exposure meters the resolved image, but `resolve: tonemapped` applies exposure before resolving");
    assert_nothing_written(&dir);
}

#[test]
fn a_gltf_file_without_lights_gets_the_default_lighting_with_a_warning() {
    let dir = temp_dir();
    let out = dir.path().join("a.png");
    let scene = "scene/tests/fixtures/hierarchy_embedded.gltf";
    render_default(&out, &["--scene", scene])
        .expect(0)
        .stderr_has("it has no lights; lit by the default lighting: a neutral studio environment");
    let lit = mean_brightness(&read_png(&out));
    let file_only = render_default(&out, &["--scene", scene, "--lights", "file"]).expect(0);
    assert!(
        !file_only.stderr.contains("default lighting"),
        "{}",
        file_only.stderr
    );
    // The fixture's material mostly emits: the default lighting adds a little.
    assert!(mean_brightness(&read_png(&out)) < lit - 1.0);
    render_default(&out, &["--scene", scene, "--lights", "sun"])
        .expect(2)
        .stderr_has("expected one of auto, file, default, both");
}

/// `explain` plans what `render` runs: a file without lights, lit by the default lighting's
/// environment, shows that environment behind it, so its plan has the background pass
/// (before, explain dropped it: the H200 plan pages of FlightHelmet left out the background
/// their timings had).
#[test]
fn explain_plans_the_environment_background_render_draws() {
    let scene = "scene/tests/fixtures/hierarchy_embedded.gltf";
    let explained = |extra: &[&str]| {
        let pipeline = ["explain", "--pipeline", "pipelines/visibility_msaa_4x.ron"];
        rgraph(&[&pipeline[..], &["--scene", scene], extra].concat())
            .expect(0)
            .stdout
    };
    let plan = explained(&[]);
    assert!(
        plan.contains("\nfeatures: alpha_mask, background, "),
        "{plan}"
    );
    assert!(plan.contains(". background (render)\n"), "{plan}");
    let on_lavapipe = explained(&["--profile", "adapter"]);
    assert!(
        on_lavapipe.contains(". background (hardware raster) (render)\n"),
        "{on_lavapipe}"
    );
}

/// The graph-file guide's pipeline written from parts only renders the lit scene, as the
/// tiled pipeline it rebuilds (plus FXAA) does.
#[test]
fn the_guide_s_pipeline_of_parts_renders() {
    let dir = temp_dir();
    let (ours, tiled) = (dir.path().join("parts.png"), dir.path().join("tiled.png"));
    render_default(&ours, &["--pipeline", "docs/examples/tiled_fxaa.ron"]).expect(0);
    render_tiled(&tiled, &[]).expect(0);
    let (ours, tiled) = (read_png(&ours), read_png(&tiled));
    assert!(
        distinct_colors(&ours) > 100,
        "{} colors",
        distinct_colors(&ours)
    );
    let (a, b) = (mean_brightness(&ours), mean_brightness(&tiled));
    assert!(
        (a - b).abs() < 0.02 * b,
        "mean brightness {a:.2} against {b:.2}"
    );
}
