//! Extreme case 8 (issue 6), the `compare` detector's thresholds at their limits.
//!
//! One knob `s` sets all three: `depth_threshold: s`, `albedo_threshold: s`,
//! `normal_threshold: 1 - 2s` (a cosine), swept from 0 to 1, on builtin:dense and
//! builtin:spheres at 64x64.
//!
//! - Extremes: `s = 0` (any difference between samples is an edge) and `s = 1`, the
//!   largest values the parameters accept, which no sample pair can exceed (depths and
//!   albedos are >= 0, so no difference passes `> 1 x` the larger one; no cosine is below
//!   -1): in effect infinite.
//! - Expected: at 0 every pixel whose samples hold different G-buffer values (as compare
//!   sees them: albedo, view depth, flags, normals more than about 0.06 degrees apart;
//!   closer ones have a cosine of exactly 1 in f32) is marked and
//!   shaded per sample, so the image equals per-sample shading (`detector: all`) on those
//!   pixels; at 1 only pixels whose samples differ in material flags (surface against
//!   background, lit against unlit, which no threshold controls) are marked, and the
//!   image equals per-pixel shading (`detector: none`) everywhere else; in between, the
//!   marked set only shrinks as `s` grows.
//! - Bounds asserted: at 0, marked pixels are bit-identical to `detector: all` and every
//!   pixel with differing samples is marked; at 1, the marked set is exactly the
//!   flag-differing set and the other pixels are bit-identical to `detector: none`; each
//!   step's marked set is a subset of the previous one (so the count never grows).
//!
//! Measured on lavapipe (marked pixels from s = 0 to 1): builtin:dense 2145, 2113, 2087,
//! 2008, 1903, 1885, 1878, 1826, 442, 64; builtin:spheres 1159, 1122, 1036, 650, 291,
//! 225, 218, 215, 130, 62.

use crate::deferred_support;
use crate::deferred_support::measure;

use deferred_support::{gpu, Render};
use rgraph_core::gpu::Gpu;

const SIZE: (u32, u32) = (64, 64);
const SWEEP: [f32; 10] = [0.0, 1e-4, 1e-3, 3e-3, 0.01, 0.03, 0.1, 0.3, 0.6, 1.0];
/// A cosine in f32 cannot tell normals apart closer than about 0.02 degrees (1 - 6e-8 is
/// the largest f32 below 1): neighbouring encodings (2^-24 apart near 0) have a cosine
/// of exactly 1, so no threshold separates them. Differences above this (about 0.06
/// degrees) are visible to it.
const NORMAL_RESOLUTION: f32 = 1e-3;
const DETECTOR: &str = "params: (detector: compare),";

struct Frame {
    marked: Vec<bool>,
    color: Vec<[u8; 4]>,
}

/// The edge pass's G-buffer inputs, which `all` and `none` do not read.
const GBUFFER_INPUTS: &str =
    "\"albedo\": \"albedo\", \"normal\": \"normal\", \"material\": \"material\",
                \"view_depth\": \"view_depth\", \"depth\": \"depth\",
            },
            outputs: { \"depth\": \"depth_edges\" },";
const DEPTH_INPUT: &str = "\"depth\": \"depth\",
            },
            outputs: { \"depth\": \"depth_edges\" },";

fn render<'a>(scene: &'a str, params: &'a str) -> Render<'a> {
    let render = Render::new("deferred_msaa_4x.ron", scene, SIZE).edit(DETECTOR, params);
    if params.contains("compare") {
        render
    } else {
        render.edit(GBUFFER_INPUTS, DEPTH_INPUT)
    }
}

fn frame(gpu: &Gpu, render: Render) -> Frame {
    let mut images = render.read(gpu, &["color", "debug.edges"]);
    let edges = images.remove(1);
    Frame {
        marked: measure::marked(&edges),
        color: images.remove(0).pixels,
    }
}

/// Per pixel: (whether its samples differ in what `compare` looks at, whether they
/// differ in material flags). What it looks at: albedo, view depth, flags, and normals
/// whose octahedral encodings differ by more than [`NORMAL_RESOLUTION`].
fn sample_differences(gpu: &Gpu, scene: &str) -> Vec<(bool, bool)> {
    let frame = Render::new("deferred_msaa_4x.ron", scene, SIZE)
        .edit(
            "outputs: [\"color\",",
            "outputs: [\"albedo\", \"normal\", \"material\", \"view_depth\", \"color\",",
        )
        .run(gpu);
    let targets: Vec<Vec<Vec<[f32; 4]>>> = ["albedo", "normal", "material", "view_depth"]
        .iter()
        .map(|t| frame.samples(gpu, t))
        .collect();
    let flags = |s: &[f32; 4]| (s[2] * 255.0).round() as u32;
    (0..(SIZE.0 * SIZE.1) as usize)
        .map(|i| {
            let [albedo, normal, material, depth] = [0, 1, 2, 3].map(|t| &targets[t][i]);
            let flags_differ = material.iter().any(|s| flags(s) != flags(&material[0]));
            let differ = flags_differ
                || albedo.iter().any(|s| s[..3] != albedo[0][..3])
                || depth.iter().any(|s| s[0] != depth[0][0])
                || normal.iter().any(|s| {
                    (s[0] - normal[0][0]).abs().max((s[1] - normal[0][1]).abs()) > NORMAL_RESOLUTION
                });
            (differ, flags_differ)
        })
        .collect()
}

fn xy(i: usize) -> (u32, u32) {
    (i as u32 % SIZE.0, i as u32 / SIZE.0)
}

#[test]
fn thresholds_from_zero_to_infinity() {
    let gpu = gpu();
    for scene in ["builtin:dense", "builtin:spheres"] {
        let differences = sample_differences(&gpu, scene);
        let per_sample = frame(&gpu, render(scene, "params: (detector: all),"));
        let per_pixel = frame(&gpu, render(scene, "params: (detector: none),"));
        let mut counts = Vec::new();
        let mut previous: Option<Vec<bool>> = None;
        for s in SWEEP {
            let params = format!(
                "params: (detector: compare, depth_threshold: {s:?}, albedo_threshold: \
                 {s:?}, normal_threshold: {:?}),",
                1.0 - 2.0 * s
            );
            let f = frame(&gpu, render(scene, &params));
            let count = f.marked.iter().filter(|&&m| m).count();
            counts.push(format!("{s}: {count}"));
            if let Some(previous) = &previous {
                let grown: Vec<(u32, u32)> = (0..f.marked.len())
                    .filter(|&i| f.marked[i] && !previous[i])
                    .map(xy)
                    .collect();
                assert!(
                    grown.is_empty(),
                    "{scene}: raising the thresholds to {s} marks {} new pixels, e.g. {:?}",
                    grown.len(),
                    &grown[..grown.len().min(8)]
                );
            }
            if s == 0.0 {
                for (i, &(differ, _)) in differences.iter().enumerate() {
                    assert!(
                        !differ || f.marked[i],
                        "{scene}: at threshold 0 pixel {:?}, whose samples differ, is not \
                         marked",
                        xy(i)
                    );
                    assert!(
                        !f.marked[i] || f.color[i] == per_sample.color[i],
                        "{scene}: at threshold 0 marked pixel {:?} is {:?}, per-sample \
                         shading gives {:?}",
                        xy(i),
                        f.color[i],
                        per_sample.color[i]
                    );
                }
            }
            if s == 1.0 {
                for (i, &(_, flags_differ)) in differences.iter().enumerate() {
                    assert_eq!(
                        f.marked[i],
                        flags_differ,
                        "{scene}: at the largest thresholds pixel {:?} is marked: {}, its \
                         samples' flags differ: {flags_differ}",
                        xy(i),
                        f.marked[i]
                    );
                    assert!(
                        f.marked[i] || f.color[i] == per_pixel.color[i],
                        "{scene}: at the largest thresholds unmarked pixel {:?} is {:?}, \
                         per-pixel shading gives {:?}",
                        xy(i),
                        f.color[i],
                        per_pixel.color[i]
                    );
                }
            }
            previous = Some(f.marked);
        }
        let differing = differences.iter().filter(|d| d.0).count();
        let flags = differences.iter().filter(|d| d.1).count();
        println!(
            "{scene}: marked pixels by threshold: {}; samples differ in {differing} pixels, \
             flags in {flags}",
            counts.join(", ")
        );
    }
}
