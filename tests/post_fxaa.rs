//! FXAA 3.11 (`fxaa`, passes/fxaa.rs) on images drawn by a generic `fullscreen` pass into
//! the sRGB target it filters: a constant image comes out unchanged, and the aliased edge
//! of a rotated square comes out closer to its exact coverage; plus the pipelines that
//! run it after deferred shading.

use std::path::PathBuf;

use rgraph_core::file::{load_str_with, GraphParams, Registry};
use rgraph_core::gpu::{read_rgba8, Executor, Imports};
use rgraph_core::{CompileOptions, CompiledGraph};

use crate::deferred_support::measure::pixels_within;
use crate::deferred_support::{gpu, srgb8, Render};

const N: u32 = 64;

/// The test image: a constant color, or a white square on black rotated by ANGLE about
/// the image's center, each pixel white where its center is inside (aliased).
const SHADER: &str = r#"
@group(0) @binding(0) var<uniform> u: vec4<f32>;

@fragment
fn fs_constant() -> @location(0) vec4<f32> {
    return vec4<f32>(u.rgb, 1.0);
}

// u = (center x, center y, half side, angle), in pixels and radians.
@fragment
fn fs_square(@builtin(position) p: vec4<f32>) -> @location(0) vec4<f32> {
    let d = p.xy - u.xy;
    let c = cos(u.w);
    let s = sin(u.w);
    let q = vec2<f32>(c * d.x + s * d.y, -s * d.x + c * d.y);
    let inside = max(abs(q.x), abs(q.y)) <= u.z;
    return select(vec4<f32>(0.0, 0.0, 0.0, 1.0), vec4<f32>(1.0), inside);
}
"#;

const SQUARE: [f32; 4] = [32.0, 32.0, 19.0, 0.35];

/// Draws `entry` of [`SHADER`] with uniform `u` into "ldr" (rgba8unorm-srgb), runs `fxaa`
/// with `params` on it, and reads back both images (RGBA8, sRGB-encoded).
fn filter(entry: &str, u: [f32; 4], params: &str) -> (Vec<[u8; 4]>, Vec<[u8; 4]>) {
    filter_as("rgba8unorm-srgb", entry, u, params)
}

/// [`filter`] with "ldr" and "color" of `format`.
fn filter_as(format: &str, entry: &str, u: [f32; 4], params: &str) -> (Vec<[u8; 4]>, Vec<[u8; 4]>) {
    let dir = std::env::temp_dir().join(format!("rgraph-fxaa-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a temporary folder");
    std::fs::write(dir.join("image.wgsl"), SHADER).expect("a writable temporary folder");
    let values: Vec<String> = u.iter().map(|v| format!("{v:?}")).collect();
    let graph = format!(
        r#"Graph(
    resources: {{
        "ldr": Texture(format: "{format}"),
        "color": Texture(format: "{format}"),
    }},
    passes: [
        (name: "image", plugin: "fullscreen",
         params: (shader: "image.wgsl", entry: "{entry}",
                  bindings: [Uniform(group: 0, binding: 0, values: [{}])]),
         outputs: {{ "color": "ldr" }}),
        (name: "fxaa", plugin: "fxaa", params: {params},
         inputs: {{ "ldr": "ldr" }}, outputs: {{ "color": "color" }}),
    ],
    outputs: ["ldr", "color"],
)"#,
        values.join(", ")
    );
    let gpu = gpu();
    let mut registry = Registry::with_builtins();
    rgraph_passes::register(&mut registry, None);
    let path: PathBuf = dir.join("fxaa.ron");
    let loaded = load_str_with(&path, &graph, &registry, &GraphParams::new())
        .unwrap_or_else(|e| panic!("cannot load the FXAA graph:\n{e}"));
    let options = CompileOptions {
        output_size: (N, N),
        profile: gpu.profile(),
    };
    let mut compiled = CompiledGraph::new(loaded, &options)
        .unwrap_or_else(|e| panic!("cannot compile the FXAA graph:\n{e}"));
    let mut executor = Executor::new(&gpu);
    executor
        .execute(&mut compiled, &Imports::new())
        .unwrap_or_else(|e| panic!("the FXAA graph failed on the device: {e}"));
    let read = |name: &str| {
        let handle = compiled.graph().names.texture(name).expect("a texture");
        let texture = executor
            .texture(compiled.plan(), handle.id())
            .expect("an exported texture");
        read_rgba8(&gpu.device, &gpu.queue, texture).expect("a readback")
    };
    (read("ldr"), read("color"))
}

/// The square's exact coverage of each pixel (16 x 16 samples), sRGB-encoded.
fn exact_square() -> Vec<[u8; 4]> {
    let [cx, cy, half, angle] = SQUARE.map(f64::from);
    let (s, c) = angle.sin_cos();
    let mut pixels = Vec::new();
    for y in 0..N {
        for x in 0..N {
            let mut inside = 0;
            for j in 0..16 {
                for i in 0..16 {
                    let dx = f64::from(x) + (f64::from(i) + 0.5) / 16.0 - cx;
                    let dy = f64::from(y) + (f64::from(j) + 0.5) / 16.0 - cy;
                    let (qx, qy) = (c * dx + s * dy, -s * dx + c * dy);
                    inside += i32::from(qx.abs().max(qy.abs()) <= half);
                }
            }
            let v = srgb8(f64::from(inside) / 256.0);
            pixels.push([v, v, v, 255]);
        }
    }
    pixels
}

/// The sum over all pixels of the absolute red difference, in 8-bit sRGB units.
fn error(image: &[[u8; 4]], exact: &[[u8; 4]]) -> u64 {
    (image.iter().zip(exact))
        .map(|(a, b)| u64::from(a[0].abs_diff(b[0])))
        .sum()
}

/// A constant image has no edge: every preset returns it unchanged, bit for bit, from an
/// sRGB target or a plain one.
#[test]
fn fxaa_leaves_a_constant_image_unchanged() {
    for format in ["rgba8unorm-srgb", "rgba8unorm"] {
        for preset in [10, 12, 29, 39] {
            let (ldr, color) = filter_as(
                format,
                "fs_constant",
                [0.8, 0.3, 0.05, 1.0],
                &format!("(preset: {preset})"),
            );
            let changed = (ldr.iter().zip(&color)).filter(|(a, b)| a != b).count();
            assert_eq!(
                changed, 0,
                "{format}, preset {preset}: {changed} pixels changed"
            );
            if format == "rgba8unorm-srgb" {
                assert_eq!(ldr[0], [srgb8(0.8), srgb8(0.3), srgb8(0.05), 255]);
            }
        }
    }
}

/// The rotated square's staircase edge: FXAA brings the image closer to the exact
/// coverage (the total error at least halved for the default preset and the finest;
/// measured on lavapipe: 12,468 before, 4,712 and 5,024 after), while pixels far from
/// the edge stay exactly as drawn.
#[test]
fn fxaa_reduces_the_edge_error_of_a_rotated_square() {
    let exact = exact_square();
    for preset in [12, 39] {
        let (aliased, filtered) = filter("fs_square", SQUARE, &format!("(preset: {preset})"));
        let (before, after) = (error(&aliased, &exact), error(&filtered, &exact));
        assert!(
            before > 1000,
            "the aliased square should be far from exact (error {before})"
        );
        assert!(
            (after as f64) < 0.5 * before as f64,
            "preset {preset}: error {after} after FXAA, {before} before"
        );
        // Pixels two or more pixels away from every aliased edge pixel are flat.
        let far = (0..N * N).filter(|&i| {
            let (x, y) = ((i % N) as i64, (i / N) as i64);
            let value = aliased[i as usize];
            (-2..=2).all(|dy| {
                (-2..=2).all(|dx| {
                    let (u, v) = (x + dx, y + dy);
                    let inside = (0..N as i64).contains(&u) && (0..N as i64).contains(&v);
                    !inside || aliased[(v as u32 * N + u as u32) as usize] == value
                })
            })
        });
        for i in far {
            assert_eq!(
                filtered[i as usize],
                aliased[i as usize],
                "preset {preset} changed a flat pixel ({}, {})",
                i % N,
                i / N
            );
        }
    }
}

/// A preset FXAA 3.11 does not have, and parameters out of range, are errors at load time
/// naming the pass and the parameter.
#[test]
fn fxaa_refuses_unknown_presets_and_bad_parameters() {
    let mut registry = Registry::with_builtins();
    rgraph_passes::register(&mut registry, None);
    // The FXAA part, checked on its own as `rgraph validate` checks it.
    let text = std::fs::read_to_string(
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("pipelines/parts/fxaa.ron"),
    )
    .expect("pipelines/parts/fxaa.ron");
    for (params, expected) in [
        ("(preset: 16)", "FXAA quality preset 16 does not exist"),
        (
            "(preset: 12, subpix: 1.5)",
            "FXAA's subpix is 1.5, but must be between 0 and 1",
        ),
        (
            "(edge_threshold: 0.01)",
            "FXAA's edge_threshold is 0.01, but must be between 0.0625 and 0.5",
        ),
        ("(quality: 12)", "quality"),
    ] {
        let edited = text.replace("params: (preset: 12)", &format!("params: {params}"));
        let Err(error) = load_str_with(
            "pipelines/parts/fxaa.ron",
            &edited,
            &registry,
            &GraphParams::new(),
        ) else {
            panic!("{params} was accepted");
        };
        let error = error.to_string();
        assert!(
            error.contains("pass \"fxaa\"") && error.contains(expected),
            "{params}: {error}"
        );
    }
}

/// The FXAA pipelines render the lit scene: FXAA changes some pixels (the edges) and
/// leaves most as the pipeline without it drew them.
#[test]
fn fxaa_pipelines_filter_the_deferred_image() {
    let gpu = gpu();
    for (plain, with_fxaa) in [
        ("deferred_noaa.ron", "deferred_noaa_fxaa.ron"),
        ("deferred_msaa_4x.ron", "deferred_msaa_4x_fxaa.ron"),
        // A preset: the visibility pipeline with FXAA added after its tone mappers.
        ("visibility_msaa_4x.ron", "visibility_msaa_4x_fxaa.ron"),
    ] {
        let a = Render::new(plain, "builtin:spheres", (96, 64)).read(&gpu, &["color"]);
        let b = Render::new(with_fxaa, "builtin:spheres", (96, 64)).read(&gpu, &["color"]);
        let total = a[0].pixels.len();
        let same = pixels_within(&a[0], &b[0], 0);
        assert!(same < total, "{with_fxaa} changed no pixel");
        assert!(
            same * 10 > total * 8,
            "{with_fxaa} changed {} of {total} pixels",
            total - same
        );
    }
}
