//! `builtin:unlit` through the deferred MSAA pipelines, against the exact coverage
//! computed on the CPU (tests/deferred_support/unlit.rs): resolved colors, and how many
//! pixels each edge detector marks.

use crate::deferred_support;

use deferred_support::unlit::{Coverage, Judged};
use deferred_support::{gpu, srgb8, PipelineFile, Render};
use rgraph_passes::{Exposure, Overrides};
use rgraph_scene::Scene;

const N: u32 = 64;
const RED: [u8; 4] = [255, 0, 0, 255];
const BLUE: [u8; 4] = [0, 0, 255, 255];

/// The edge pass's parameters and inputs in deferred_msaa_4x.ron, and with detector none.
const COMPARE_EDGES: &str = r#"params: (detector: compare),
            inputs: {
                "albedo": "albedo", "normal": "normal", "material": "material",
                "view_depth": "view_depth", "depth": "depth",
            },"#;
const NO_EDGES: &str = r#"params: (detector: none),
            inputs: { "depth": "depth" },"#;

fn coverage() -> Coverage {
    Coverage::of(
        &Scene::load("builtin:unlit").expect("builtin:unlit loads"),
        N,
    )
}

/// Linear output: no tone curve, exposure 1, so the output is the resolved color.
fn linear() -> Overrides {
    Overrides {
        tonemap: Some("none".into()),
        exposure: Some(Exposure::Fixed(1.0)),
        ..Overrides::default()
    }
}

/// Every pixel is the average of its samples' colors at the standard 4x positions
/// (unlit colors reach the HDR target per sample from the G-buffer pass; the box resolve
/// averages them), within 1/255 after sRGB encoding. Pixels with a sample too close to an
/// edge to call are skipped, and there must be few of them.
#[test]
fn unlit_pixels_are_the_average_of_their_covered_samples() {
    unlit_pixels_average_their_samples("deferred_msaa_4x.ron".into());
}

/// The same through the tiled compute pass, which resolves as it lights (compiled for
/// no features, so the pass runs although the scene is unlit).
#[test]
fn unlit_pixels_through_the_tiled_pass_are_the_average_of_their_covered_samples() {
    unlit_pixels_average_their_samples("deferred_msaa_4x_tiled.ron".into());
}

pub fn unlit_pixels_average_their_samples(pipeline: PipelineFile<'_>) {
    let gpu = gpu();
    let coverage = coverage();
    let image = Render::new(pipeline, "builtin:unlit", (N, N))
        .overrides(linear())
        .read(&gpu, &["color"])
        .remove(0);
    let (mut judged, mut partial, mut wrong) = (0, 0, Vec::new());
    for y in 0..N {
        for x in 0..N {
            if coverage.is_ambiguous(x, y) {
                continue;
            }
            judged += 1;
            let linear = coverage.resolved(x, y);
            partial += usize::from(linear.iter().any(|&c| c > 0.0 && c < 1.0));
            let expected = linear.map(srgb8);
            let got = image.at(x, y);
            let off = (0..3).any(|c| expected[c].abs_diff(got[c]) > 1);
            if off {
                wrong.push(format!("({x}, {y}): expected {expected:?}, got {got:?}"));
            }
        }
    }
    assert!(
        judged >= (N * N) as usize * 95 / 100,
        "only {judged} of {} pixels could be judged",
        N * N
    );
    assert!(
        partial > 50,
        "only {partial} partially covered pixels: the test proves little"
    );
    assert!(
        wrong.is_empty(),
        "{pipeline}: {} of {judged} pixels differ from the sample average by more than 1/255 \
         ({partial} are partially covered), e.g.:\n{}",
        wrong.len(),
        wrong
            .iter()
            .take(10)
            .cloned()
            .collect::<Vec<_>>()
            .join("\n")
    );
}

/// The edge-pixel counts of the detectors on a scene whose partially covered pixels are
/// known: `all` marks every pixel, `none` none, `compare` exactly the pixels whose
/// samples see different surfaces, `coverage` exactly the pixels with a visible sample
/// from a triangle that does not cover the whole pixel (triangle edges inside a shape
/// included; the yellow-blue intersection excluded), and `centroid` no more than those.
/// Measured on lavapipe at 64x64: all 4096, none 0, compare 238, coverage 255, centroid
/// 255 (lavapipe moves the centroid off the center whenever a sample is uncovered).
#[test]
fn edge_detectors_mark_the_known_pixels() {
    let gpu = gpu();
    let coverage = coverage();
    let edges = |pipeline: &str, edit: Option<(&str, &str)>| {
        let mut render = Render::new(pipeline, "builtin:unlit", (N, N));
        if let Some((from, to)) = edit {
            render = render.edit(from, to);
        }
        let image = render.read(&gpu, &["debug.edges"]).remove(0);
        assert_eq!(
            image.count(RED) + image.count(BLUE) + image.count([0, 0, 0, 255]),
            (N * N) as usize,
            "{pipeline}: debug.edges holds colors other than red, blue and black"
        );
        image
    };
    let all = edges("deferred_per_sample_4x.ron", None).count(RED);
    // Detector none reads no G-buffer texture, so its pass takes only the depth slot.
    let none = edges("deferred_msaa_4x.ron", Some((COMPARE_EDGES, NO_EDGES))).count(RED);
    let compare = edges("deferred_msaa_4x.ron", None);
    let coverage_image = edges("deferred_msaa_4x_coverage.ron", None);
    let centroid = edges("deferred_msaa_4x_centroid.ron", None).count(RED);
    assert_eq!(all, (N * N) as usize, "detector all must mark every pixel");
    assert_eq!(none, 0, "detector none must mark no pixel");

    let Judged {
        marked,
        expected,
        wrong,
    } = coverage.judge(&compare, RED, Coverage::is_mixed);
    assert!(
        wrong.is_empty(),
        "compare marked {marked} unambiguous pixels, {expected} see several surfaces; \
         differences:\n{}",
        wrong.join("\n")
    );
    let Judged {
        marked: covered,
        expected: partial,
        wrong,
    } = coverage.judge(&coverage_image, RED, Coverage::is_partially_covered);
    assert!(
        wrong.is_empty(),
        "coverage marked {covered} unambiguous pixels, {partial} have a partially covering \
         visible triangle; differences:\n{}",
        wrong.join("\n")
    );
    let ambiguous = coverage.ambiguous_count();
    assert!(
        centroid <= coverage_image.count(RED),
        "centroid marked {centroid} pixels, more than the {} partially covered ones",
        coverage_image.count(RED)
    );
    eprintln!(
        "edge pixels of builtin:unlit at {N}x{N}: all {all}, none {none}, compare {}, \
         coverage {}, centroid {centroid} ({ambiguous} ambiguous pixels not judged)",
        compare.count(RED),
        coverage_image.count(RED)
    );
}
