//! The 16-sample reference (lavapipe, 96x64, builtin:spheres and builtin:dense): it is
//! deterministic, its 2x2 downsample is the exact average of 4 texels, and it ranks
//! deferred shading without anti-aliasing below deferred MSAA at edges.

use crate::deferred_support;
use crate::deferred_support::measure;

use deferred_support::{gpu, Render};
use measure::{diff, marked};

const SIZE: (u32, u32) = (96, 64);
const SCENES: [&str; 2] = ["builtin:spheres", "builtin:dense"];

/// deferred_noaa's mean edge error against the reference is at least this many times
/// deferred_msaa_4x's.
const NOAA_FACTOR: f64 = 2.0;

#[test]
fn reference_against_itself_has_zero_error() {
    let gpu = gpu();
    for scene in SCENES {
        let render = Render::new("reference_ssaa16.ron", scene, SIZE);
        let first = render.read(&gpu, &["color"]).remove(0);
        let second = render.read(&gpu, &["color"]).remove(0);
        let d = diff(&first, &second, None);
        println!("{scene} {}x{}: reference vs itself: {d}", SIZE.0, SIZE.1);
        assert!(
            d.max == 0,
            "{scene}: two renders of reference_ssaa16 differ: {d}"
        );
    }
}

/// The blit with a Linear filter samples the 2x-size resolve at the corner its 2x2 block
/// shares, so each output texel must be the plain average of the block's 4 texels.
#[test]
fn downsample_averages_exactly_four_texels() {
    let gpu = gpu();
    let frame = Render::new("reference_ssaa16.ron", "builtin:dense", SIZE)
        .edit(
            "outputs: [\"color\"]",
            "outputs: [\"resolved_2x\", \"resolved\", \"color\"]",
        )
        .run(&gpu);
    let big = frame.hdr(&gpu, "resolved_2x");
    let small = frame.hdr(&gpu, "resolved");
    let (w, h) = SIZE;
    assert_eq!(
        big.len(),
        (4 * w * h) as usize,
        "resolved_2x is not 2x the output size"
    );
    let mut worst = (0.0f32, 0, 0, 0);
    for y in 0..h {
        for x in 0..w {
            let texel = |dx: u32, dy: u32| big[((2 * y + dy) * 2 * w + 2 * x + dx) as usize];
            let blitted = small[(y * w + x) as usize];
            for (c, got) in blitted.into_iter().enumerate().take(3) {
                let average =
                    (texel(0, 0)[c] + texel(1, 0)[c] + texel(0, 1)[c] + texel(1, 1)[c]) / 4.0;
                // An exact average rounded to half float is off by half an ulp (2^-11
                // relative); lavapipe's filter rounds once more. Allow 2 ulps: weights off
                // by one 8-bit filter step (1/256) would miss by several at edges.
                let error = (got - average).abs() / (average.abs() * 2f32.powi(-9) + 1e-4);
                if error > worst.0 {
                    worst = (error, x, y, c);
                }
            }
        }
    }
    println!("worst error of the 2x2 average, in units of the tolerance: {worst:?}");
    assert!(
        worst.0 <= 1.0,
        "the Linear blit of resolved_2x is not the average of 2x2 texels at ({}, {}) channel {}: \
         off by {:.2} tolerances",
        worst.1,
        worst.2,
        worst.3,
        worst.0
    );
}

#[test]
fn noaa_has_more_edge_error_than_msaa() {
    let gpu = gpu();
    for scene in SCENES {
        let reference = Render::new("reference_ssaa16.ron", scene, SIZE)
            .read(&gpu, &["color"])
            .remove(0);
        let mut images =
            Render::new("deferred_msaa_4x.ron", scene, SIZE).read(&gpu, &["color", "debug.edges"]);
        let (msaa, edges) = (images.remove(0), images.remove(0));
        let edges = marked(&edges);
        let noaa = Render::new("deferred_noaa.ron", scene, SIZE)
            .read(&gpu, &["color"])
            .remove(0);
        let (msaa_error, noaa_error) = (
            diff(&msaa, &reference, Some(&edges)),
            diff(&noaa, &reference, Some(&edges)),
        );
        println!(
            "{scene} {}x{}: edge error vs reference_ssaa16: deferred_msaa_4x {msaa_error}; \
             deferred_noaa {noaa_error}; whole image: msaa {}, noaa {}",
            SIZE.0,
            SIZE.1,
            diff(&msaa, &reference, None),
            diff(&noaa, &reference, None),
        );
        assert!(
            noaa_error.mean >= NOAA_FACTOR * msaa_error.mean,
            "{scene}: over the {} edge pixels deferred_msaa_4x marks, deferred_noaa's mean \
             error against reference_ssaa16 ({:.2}) is not {NOAA_FACTOR}x deferred_msaa_4x's \
             ({:.2}); noaa: {noaa_error}; msaa: {msaa_error}",
            msaa_error.pixels,
            noaa_error.mean,
            msaa_error.mean
        );
    }
}
