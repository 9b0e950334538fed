//! Extreme case 10 (issue 6), determinism: the same inputs give bit-identical results
//! across runs.
//!
//! - Extreme: the same pipeline, scene, size and view rendered again, by a new process
//!   (`rgraph render`, the built binary) and by the library within one process.
//! - Expected: the PNG files are byte-identical (no time, address or hash-order
//!   dependence reaches a pixel or the file), and the library's read-backs (8-bit images
//!   and the half-float HDR targets) are bit-identical.
//! - Bound asserted: 0 differing bytes.

use crate::deferred_support;

use std::process::Command;

use deferred_support::{gpu, Render};

/// `rgraph render` with `args` at 64x48 into a fresh file; returns the PNG's bytes.
fn render_png(dir: &std::path::Path, name: &str, args: &[&str]) -> Vec<u8> {
    let out = dir.join(name);
    let run = Command::new(env!("CARGO_BIN_EXE_rgraph"))
        .arg("render")
        .args(["--width", "64", "--height", "48", "--out"])
        .arg(&out)
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("the rgraph binary runs");
    assert!(
        run.status.success(),
        "rgraph render {args:?} failed:\n{}",
        String::from_utf8_lossy(&run.stderr)
    );
    std::fs::read(&out).unwrap_or_else(|e| panic!("cannot read {}: {e}", out.display()))
}

/// The first byte where `a` and `b` differ, or a length mismatch.
fn first_difference(a: &[u8], b: &[u8]) -> Option<usize> {
    a.iter()
        .zip(b)
        .position(|(x, y)| x != y)
        .or((a.len() != b.len()).then_some(a.len().min(b.len())))
}

/// Two processes rendering the same frame write byte-identical PNGs: the default
/// pipeline and its luminance-weighted and per-sample variants, lit scenes with point,
/// spot and many lights, the final image and the edge view.
#[test]
fn rgraph_render_twice_writes_identical_pngs() {
    let dir = tempfile::tempdir().expect("a temporary directory");
    let cases: [&[&str]; 5] = [
        &[],
        &["--scene", "builtin:dense", "--view", "edges"],
        &["--scene", "builtin:lights?count=64"],
        &[
            "--pipeline",
            "pipelines/deferred_msaa_4x_tonemapped_resolve.ron",
            "--scene",
            "builtin:dense",
        ],
        &["--pipeline", "pipelines/deferred_per_sample_4x.ron"],
    ];
    for (i, args) in cases.iter().enumerate() {
        let first = render_png(dir.path(), &format!("{i}-a.png"), args);
        let second = render_png(dir.path(), &format!("{i}-b.png"), args);
        assert!(first.len() > 100, "{args:?}: a {} byte PNG", first.len());
        if let Some(at) = first_difference(&first, &second) {
            panic!(
                "rgraph render {args:?} wrote different PNGs on two runs ({} and {} bytes), \
                 first difference at byte {at}",
                first.len(),
                second.len()
            );
        }
    }
}

/// Rendering twice through the library in one process (a new graph, executor and scene
/// upload each time, the same device) gives bit-identical 8-bit outputs and HDR targets.
#[test]
fn the_library_renders_the_same_bits_twice() {
    let gpu = gpu();
    // The single-sampled HDR target each pipeline has: the resolve's output, or the lit
    // target itself without MSAA.
    for (pipeline, scene, hdr) in [
        ("deferred_msaa_4x.ron", "builtin:spheres", "resolved"),
        (
            "deferred_msaa_4x_sample_mask.ron",
            "builtin:dense",
            "resolved",
        ),
        (
            "deferred_msaa_4x_tonemapped_resolve.ron",
            "builtin:lights?count=64",
            "resolved",
        ),
        ("deferred_noaa.ron", "builtin:spheres", "hdr_lit"),
    ] {
        let export = format!("outputs: [\"{hdr}\", \"color\",");
        let render = || {
            let frame = Render::new(pipeline, scene, (48, 40))
                .edit("outputs: [\"color\",", &export)
                .run(&gpu);
            let hdr: Vec<u32> = frame
                .hdr(&gpu, hdr)
                .iter()
                .flatten()
                .map(|c| c.to_bits())
                .collect();
            let color = frame.image(&gpu, "color").pixels;
            let edges = frame.image(&gpu, "debug.edges").pixels;
            (hdr, color, edges)
        };
        let (a, b) = (render(), render());
        let hdr_diff = a.0.iter().zip(&b.0).filter(|(x, y)| x != y).count();
        let color_diff = a.1.iter().zip(&b.1).filter(|(x, y)| x != y).count();
        let edge_diff = a.2.iter().zip(&b.2).filter(|(x, y)| x != y).count();
        assert_eq!(
            (hdr_diff, color_diff, edge_diff),
            (0, 0, 0),
            "{pipeline} {scene}: (resolved HDR channels, color pixels, edge pixels) that \
             differ between two renders"
        );
    }
}
