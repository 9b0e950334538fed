//! Extreme case 7 (issue 6), sizes and sample counts.
//!
//! - Extremes: 1x1; odd sizes 1x4097 and 4097x1; the adapter's largest 2D texture
//!   dimension as one row and one column (16384 on lavapipe; the full 16384x16384 square
//!   would need 34 GB for the 4x G-buffer alone, 32 bytes per sample, more than a lavapipe
//!   CI machine has, so only the thin extremes run); a size of 0; every sample count the
//!   device offers for all of the pipeline's formats; the counts it does not.
//! - Expected: the frames render with the output's exact size and a finite, non-black
//!   resolved image; a 0 width or height is a usage error of `rgraph render` and
//!   unsupported counts are compile errors, each naming the problem, before any GPU work.
//! - Bounds asserted: resolved HDR finite and within [0, 65504] in every pixel; some light
//!   in every frame; the errors' texts.
//!
//! The command line checks the same limits: tests/cli_render.rs
//! (`sizes_must_be_at_least_one_pixel`, `sizes_above_the_device_limit_fail_before_rendering`)
//! and tests/cli_render_samples.rs (8x on lavapipe lists the counts it has).

use crate::deferred_support;

use std::path::Path;
use std::sync::Arc;

use deferred_support::{gpu, Render};
use rgraph_core::file::{load_file_with, GraphParams, Registry};
use rgraph_core::gpu::Gpu;
use rgraph_core::CompileOptions;
use rgraph_passes::{Host, Overrides};
use rgraph_scene::Scene;

/// The deferred pipeline's formats, each at the sample count the pipeline gives it.
const FORMATS: [wgpu::TextureFormat; 6] = [
    wgpu::TextureFormat::Rgba8UnormSrgb,
    wgpu::TextureFormat::Rg16Float,
    wgpu::TextureFormat::Rgba8Unorm,
    wgpu::TextureFormat::R32Float,
    wgpu::TextureFormat::Rgba16Float,
    wgpu::TextureFormat::Depth32FloatStencil8,
];

/// Renders deferred_msaa_4x at `samples` samples (its `msaa` parameter) and checks the
/// resolved image.
fn render_checked(gpu: &Gpu, size: (u32, u32), samples: u32) {
    let frame = Render::new("deferred_msaa_4x.ron", "builtin:spheres", size)
        .export_resolved()
        .param("msaa", samples)
        .run(gpu);
    let hdr = frame.hdr(gpu, "resolved");
    let color = frame.image(gpu, "color");
    assert_eq!(
        (color.width, color.height),
        size,
        "{samples}x at {size:?}: the output's size"
    );
    assert_eq!(hdr.len(), (size.0 * size.1) as usize);
    if let Some(i) = hdr.iter().position(|p| {
        p.iter()
            .any(|c| !c.is_finite() || !(0.0..=65504.0).contains(c))
    }) {
        panic!("{samples}x at {size:?}: resolved pixel {i} is {:?}", hdr[i]);
    }
    let lit = hdr.iter().filter(|p| p[0] + p[1] + p[2] > 0.0).count();
    assert!(lit > 0, "{samples}x at {size:?}: the frame is black");
}

/// 1x1, 1x4097, 4097x1 and a row and a column of the adapter's largest dimension.
#[test]
fn one_pixel_odd_and_largest_sizes_render() {
    let gpu = gpu();
    let largest = gpu.device.limits().max_texture_dimension_2d;
    for size in [(1, 1), (1, 4097), (4097, 1), (largest, 1), (1, largest)] {
        render_checked(&gpu, size, 4);
    }
}

/// The sample counts the device supports for every format of the deferred pipeline.
fn offered(gpu: &Gpu) -> Vec<u32> {
    [1, 2, 4, 8, 16]
        .into_iter()
        .filter(|&n| {
            FORMATS.iter().all(|&f| {
                gpu.adapter
                    .get_texture_format_features(f)
                    .flags
                    .sample_count_supported(n)
            })
        })
        .collect()
}

/// Every sample count the device offers renders (lavapipe: 1x and 4x).
#[test]
fn every_offered_sample_count_renders() {
    let gpu = gpu();
    let counts = offered(&gpu);
    assert!(
        counts.contains(&1) && counts.len() >= 2,
        "offered: {counts:?}"
    );
    for samples in counts {
        render_checked(&gpu, (33, 17), samples);
    }
}

/// Loads and compiles deferred_msaa_4x at `samples` samples for `gpu` at `size`; the
/// error text.
fn compile_error(gpu: &Gpu, size: (u32, u32), samples: u32) -> String {
    let host = Host::new(
        Arc::new(Scene::load("builtin:spheres").expect("builtin:spheres loads")),
        Overrides::default(),
    );
    let mut registry = Registry::with_builtins();
    rgraph_passes::register(&mut registry, Some(Arc::new(host)));
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("pipelines/deferred_msaa_4x.ron");
    let params = GraphParams::new().with("msaa", samples);
    // Counts the plugins cannot shade are refused at load, the rest by the compile.
    let loaded = match load_file_with(&path, &registry, &params) {
        Ok(loaded) => loaded,
        Err(e) => return e.to_string(),
    };
    let options = CompileOptions {
        output_size: size,
        profile: gpu.profile(),
    };
    match loaded.compile(&options) {
        Ok(_) => panic!("compiling at {size:?} with {samples} samples succeeded"),
        Err(e) => e.to_string(),
    }
}

/// A zero width or height is refused by `rgraph render` (exit 2, naming the flag) before
/// anything renders, with the default deferred pipeline. (Through the library a zero
/// output size is not an error: rgraph-core's `Size::resolve` makes every relative texture
/// at least 1 texel, so the frame renders 1 pixel wide; the command line is the guard.)
#[test]
fn a_zero_size_is_a_clear_error() {
    let dir = tempfile::tempdir().expect("a temporary directory");
    let out = dir.path().join("zero.png");
    for (width, height) in [("0", "16"), ("16", "0"), ("0", "0")] {
        let run = std::process::Command::new(env!("CARGO_BIN_EXE_rgraph"))
            .args(["render", "--width", width, "--height", height, "--out"])
            .arg(&out)
            .current_dir(env!("CARGO_MANIFEST_DIR"))
            .output()
            .expect("the rgraph binary runs");
        let stderr = String::from_utf8_lossy(&run.stderr);
        assert_eq!(run.status.code(), Some(2), "{width}x{height}: {stderr}");
        assert!(
            stderr.contains("at least 1"),
            "{width}x{height}: the error does not say why: {stderr}"
        );
        assert!(!out.exists(), "{width}x{height} wrote {}", out.display());
    }
}

/// Each sample count the device lacks (lavapipe: 2x, 8x, 16x) is an error naming the
/// count: the compile for the device lists the counts it has for each texture; 16x,
/// whose sample positions the deferred passes do not know, is refused when the file
/// loads.
#[test]
fn unsupported_sample_counts_are_clear_errors() {
    let gpu = gpu();
    let offered = offered(&gpu);
    let missing: Vec<u32> = [2, 8, 16]
        .into_iter()
        .filter(|n| !offered.contains(n))
        .collect();
    assert!(!missing.is_empty(), "the device offers every count");
    for samples in missing {
        let error = compile_error(&gpu, (16, 16), samples);
        println!("{samples}x: {error}");
        let by_device = error.contains(&format!("does not support {samples}x multisampling"))
            && error.contains("supported: ");
        let by_plugins = error.contains(&format!("{samples} samples per pixel"));
        assert!(by_device || by_plugins, "{samples}x: {error}");
    }
}
