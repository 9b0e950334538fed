//! The tiled compute lighting pass (`light_tiled`) against the fragment light passes it
//! stands beside: the same images, the same edges, culling that drops no light that
//! contributes, adaptive shading close to per-sample shading, and workgroup memory
//! checked when compiling.

use crate::common::edited_pipeline;
use crate::deferred_support;

use deferred_support::measure::{diff, marked, Diff};
use deferred_support::{gpu, Image, Render};
use rgraph_core::file::{load_str, LoadedGraph, Registry};
use rgraph_core::{CompileOptions, DeviceProfile};

const SIZE: (u32, u32) = (96, 64);

/// Lit built-in scenes and the unlit analytic one (compiled for no features, so the
/// light passes run on it too).
const SCENES: [&str; 4] = [
    "builtin:unlit",
    "builtin:spheres",
    "builtin:dense",
    "builtin:lights?count=64",
];

fn color(render: Render<'_>) -> Image {
    render.read(&gpu(), &["color"]).remove(0)
}

/// The share of pixels whose channels all lie within `tolerance` 8-bit steps.
fn within(a: &Image, b: &Image, tolerance: u8) -> (f64, Diff) {
    let close = a
        .pixels
        .iter()
        .zip(&b.pixels)
        .filter(|(p, q)| (0..3).all(|c| p[c].abs_diff(q[c]) <= tolerance))
        .count();
    (close as f64 / a.pixels.len() as f64, diff(a, b, None))
}

/// Each tiled pipeline renders its fragment twin's image within 1/255 on at least 99.5%
/// of the pixels, on every scene.
#[test]
fn tiled_pipelines_match_their_fragment_twins() {
    let twins = [
        ("deferred_msaa_4x_tiled.ron", "deferred_msaa_4x.ron"),
        ("deferred_noaa_tiled.ron", "deferred_noaa.ron"),
        (
            "deferred_per_sample_4x_tiled.ron",
            "deferred_per_sample_4x.ron",
        ),
    ];
    for (tiled, fragment) in twins {
        for scene in SCENES {
            let a = color(Render::new(tiled, scene, SIZE));
            let b = color(Render::new(fragment, scene, SIZE));
            let (share, d) = within(&a, &b, 1);
            println!(
                "{tiled} vs {fragment} on {scene}: {:.3}% within 1/255, {d}",
                share * 100.0
            );
            assert!(
                share >= 0.995,
                "{tiled} vs {fragment} on {scene}: only {:.3}% of pixels within 1/255 ({d})",
                share * 100.0
            );
        }
    }
}

/// With 1,024 lights, culling per tile changes no pixel by more than 1/255 against the
/// same pass listing every light in every tile, and the image is lit.
#[test]
fn culling_drops_no_light_that_contributes() {
    let scene = "builtin:lights?count=1024";
    let pipeline = "deferred_msaa_4x_tiled.ron";
    let lights = r#"params: (edges: (detector: compare)),"#;
    let culled = color(Render::new(pipeline, scene, SIZE));
    let everything = color(Render::new(pipeline, scene, SIZE).edit(
        lights,
        r#"params: (edges: (detector: compare), cull: false),"#,
    ));
    let d = diff(&culled, &everything, None);
    assert!(d.max <= 1, "culling changed the image: {d}");
    let lit = culled.pixels.iter().filter(|p| p[..3] != [0, 0, 0]).count();
    assert!(lit > culled.pixels.len() / 2, "only {lit} pixels lit");
    let fragment = color(Render::new("deferred_msaa_4x.ron", scene, SIZE));
    let (share, d) = within(&culled, &fragment, 1);
    assert!(
        share >= 0.995,
        "1,024 lights: only {:.3}% of pixels within 1/255 of the fragment path ({d})",
        share * 100.0
    );
}

/// Adaptive shading (each fragment of an edge pixel once, weighted by its samples) is
/// within 2/255 of per-sample shading of the edge pixels (deferred_msaa_4x_tiled, which
/// shades the rest once per pixel as the adaptive pipeline does) on at least 99% of the
/// pixels.
#[test]
fn adaptive_shading_is_close_to_per_sample_shading() {
    for scene in ["builtin:dense", "builtin:lights?count=64"] {
        let adaptive = color(Render::new("deferred_msaa_4x_adaptive.ron", scene, SIZE));
        let per_sample = color(Render::new("deferred_msaa_4x_tiled.ron", scene, SIZE));
        let (share, d) = within(&adaptive, &per_sample, 2);
        println!(
            "adaptive vs per-sample edges on {scene}: {:.3}% within 2/255, {d}",
            share * 100.0
        );
        assert!(
            share >= 0.99,
            "{scene}: only {:.3}% of pixels within 2/255 ({d})",
            share * 100.0
        );
    }
}

/// The tiled pass and the edge pass share one detector: the tiled "debug.edges" view
/// marks exactly the pixels the fragment path's stencil does, and there are some.
#[test]
fn tiled_and_stencil_edges_are_the_same_pixels() {
    for scene in ["builtin:dense", "builtin:spheres"] {
        let tiled = Render::new("deferred_msaa_4x_tiled.ron", scene, SIZE)
            .read(&gpu(), &["debug.edges"])
            .remove(0);
        let stencil = Render::new("deferred_msaa_4x.ron", scene, SIZE)
            .read(&gpu(), &["debug.edges"])
            .remove(0);
        let (a, b) = (marked(&tiled), marked(&stencil));
        let edges = a.iter().filter(|&&e| e).count();
        assert!(edges > 20, "{scene}: only {edges} edge pixels");
        assert_eq!(a, b, "{scene}: the tiled and stencil edge masks differ");
        assert_eq!(
            diff(&tiled, &stencil, None).max,
            0,
            "{scene}: the views differ off the edges (blue and black)"
        );
    }
}

/// "debug.fragments" marks every edge pixel as holding several fragments (green 2, blue
/// 3, red 4: samples the detector tells apart are never one fragment), and pixels it
/// does not tell apart too where their samples differ below its thresholds (fragments
/// are told apart exactly); "debug.tile_lights" is a heat map that is constant over
/// each 16x16 tile and lit where lights reach.
#[test]
fn fragment_and_tile_light_views() {
    let gpu = gpu();
    let scene = "builtin:lights?count=64";
    let frame = Render::new("deferred_msaa_4x_adaptive.ron", scene, SIZE).run(&gpu);
    let edges = marked(&frame.image(&gpu, "debug.edges"));
    let fragments = frame.image(&gpu, "debug.fragments");
    let several = |p: &[u8; 4]| [[0, 255, 0, 255], [0, 0, 255, 255], [255, 0, 0, 255]].contains(p);
    let split: Vec<bool> = fragments.pixels.iter().map(several).collect();
    let count = split.iter().filter(|&&s| s).count();
    assert!(count > 20, "only {count} pixels with several fragments");
    let single = (0..split.len()).find(|&i| edges[i] && !split[i]);
    assert_eq!(single, None, "an edge pixel (index) with one fragment");
    let below = (0..split.len()).filter(|&i| !edges[i] && split[i]).count();
    assert!(
        below > 100,
        "only {below} pixels off the edges with several fragments"
    );
    let heat = frame.image(&gpu, "debug.tile_lights");
    for y in 0..SIZE.1 {
        for x in 0..SIZE.0 {
            let corner = heat.at(x / 16 * 16, y / 16 * 16);
            assert_eq!(heat.at(x, y), corner, "({x}, {y}) differs from its tile");
        }
    }
    let hot = heat.pixels.iter().filter(|p| p[..3] != [0, 0, 0]).count();
    assert!(
        hot > heat.pixels.len() / 2,
        "only {hot} pixels in tiles with lights"
    );
}

/// A registry with the deferred plugins and no scene (enough to load and compile), the
/// path of pipelines/`name` and its text, for edited copies.
fn pipeline_file(name: &str) -> (Registry, String, String) {
    let mut registry = Registry::with_builtins();
    rgraph_passes::register(&mut registry, None);
    let path = format!("{}/pipelines/{name}", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).expect("the pipeline exists");
    (registry, path, text)
}

/// WebGPU's defaults as a device named `name` with one limit changed by `limit`, at
/// 64x64.
fn limited_device(name: &str, limit: impl FnOnce(&mut DeviceProfile)) -> CompileOptions {
    let mut profile = DeviceProfile::webgpu();
    limit(&mut profile);
    profile.name = name.into();
    CompileOptions {
        output_size: (64, 64),
        profile,
    }
}

/// Compiling `loaded` for `options` fails (`why` says why it must), with `expected` among
/// its errors.
fn assert_refused(loaded: &LoadedGraph, options: &CompileOptions, why: &str, expected: &str) {
    let errors = loaded.compile(options).expect_err(why).to_string();
    assert!(errors.contains(expected), "{errors}");
}

/// A tile too big for the device's workgroup memory is a compile error naming the pass
/// and the entry point; the same pass with a smaller tile compiles.
#[test]
fn workgroup_memory_overflow_is_a_compile_error_naming_the_pass() {
    let (registry, path, text) = pipeline_file("deferred_msaa_4x_tiled.ron");
    let options = limited_device("a device with 8 KiB of workgroup memory", |p| {
        p.limits.max_compute_workgroup_storage_size = 8192;
    });
    assert_refused(
        &load_str(&path, &text, &registry).expect("the file loads"),
        &options,
        "16x16 tiles at 4x need more than 8 KiB",
        "pass \"light tiled\": compute entry point \"cs_light_tiled\" uses 13440 bytes of \
         workgroup memory, more than the limit of 8192 on a device with 8 KiB of workgroup \
         memory",
    );
    // The tiled pass and its debug views, in the parts the pipeline uses.
    let smaller = edited_pipeline(
        "deferred_msaa_4x_tiled.ron",
        &[
            (
                "params: (edges: (detector: compare)),",
                "params: (edges: (detector: compare), tile: 8),",
            ),
            (
                "params: (edges: (detector: compare), view: edges),",
                "params: (view: edges, tile: 8),",
            ),
            (
                "params: (view: tile_lights),",
                "params: (view: tile_lights, tile: 8),",
            ),
        ],
    );
    // Edge entries (4 + 12 bytes for each of 64 x 3), the light batch (4 x 64), the
    // four side planes (64) and four atomics (16 each).
    let plan = load_str(&smaller.path, &smaller.text, &registry)
        .expect("the file loads")
        .compile(&options)
        .unwrap_or_else(|e| panic!("8x8 tiles fit in 8 KiB: {e}"));
    let planned = plan
        .passes
        .iter()
        .find(|p| p.name == "light tiled")
        .and_then(|p| p.workgroups.first().cloned())
        .expect("the plan has the tiled pass's workgroup");
    assert_eq!((planned.size, planned.memory_bytes), ([8, 8, 1], 3456));
    assert!(
        rgraph_core::explain::text(&plan)
            .contains("workgroup: 8x8x1 (cs_light_tiled), 3456 bytes of workgroup memory"),
        "explain shows the workgroup"
    );
    let huge = edited_pipeline(
        "deferred_msaa_4x_tiled.ron",
        &[(
            "params: (edges: (detector: compare)),",
            "params: (edges: (detector: compare), tile: 32),",
        )],
    );
    assert_refused(
        &load_str(&huge.path, &huge.text, &registry).expect("the file loads"),
        &CompileOptions::default(),
        "32x32 invocations exceed WebGPU's 256",
        "pass \"light tiled\": compute entry point \"cs_light_tiled\" runs 1024 invocations \
         per workgroup (32x32x1), more than the limit of 256",
    );
}

/// A visibility buffer's tiled pass dispatches three entry points (the list's reset, the
/// tiles, the listed edge pixels), and the compile checks each: a device allowing 128
/// invocations refuses the tiles' 16x16 even though the edge dispatch, the one with the
/// most workgroup memory, runs 128; explain lists all three.
#[test]
fn every_entry_point_the_tiled_pass_dispatches_is_checked() {
    let (registry, path, text) = pipeline_file("visibility_msaa_4x.ron");
    let loaded = load_str(&path, &text, &registry).expect("the file loads");
    let plan = loaded
        .compile(&CompileOptions::default())
        .expect("it compiles for WebGPU's defaults");
    let explained = rgraph_core::explain::text(&plan);
    for line in [
        "workgroup: 1x1x1 (cs_edge_pixels_reset), 0 bytes of workgroup memory",
        "workgroup: 16x16x1 (cs_light_tiled), 1200 bytes of workgroup memory",
        "workgroup: 128x1x1 (cs_light_edge_pixels), 7328 bytes of workgroup memory",
    ] {
        assert!(explained.contains(line), "{line} not in:\n{explained}");
    }
    let options = limited_device("a device of 128 invocations", |p| {
        p.limits.max_compute_invocations_per_workgroup = 128;
    });
    assert_refused(
        &loaded,
        &options,
        "16x16 tiles exceed 128 invocations",
        "pass \"light tiled\": compute entry point \"cs_light_tiled\" runs 256 invocations \
         per workgroup (16x16x1), more than the limit of 128",
    );
}

/// A tile side outside 2 to 32 is refused at load, naming the parameter.
#[test]
fn a_tile_of_one_pixel_is_refused() {
    let (registry, _, _) = pipeline_file("deferred_msaa_4x_tiled.ron");
    let edited = edited_pipeline(
        "deferred_msaa_4x_tiled.ron",
        &[(
            "params: (edges: (detector: compare)),",
            "params: (edges: (detector: compare), tile: 1),",
        )],
    );
    let Err(error) = load_str(&edited.path, &edited.text, &registry) else {
        panic!("a 1x1 tile has no room for its four side planes, but the file loaded");
    };
    let error = error.to_string();
    assert!(
        error.contains("pass \"light tiled\"")
            && error.contains("tile must be 2 to 32 pixels, got 1"),
        "{error}"
    );
}
