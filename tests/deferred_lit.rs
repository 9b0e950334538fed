//! Lit scenes through the deferred pipelines: finite HDR, light where there should be.

mod deferred_support;

use deferred_support::{gpu, Render};

const SIZE: (u32, u32) = (64, 64);

/// Also exports the resolved HDR target.
const EXPORT_RESOLVED: (&str, &str) =
    ("outputs: [\"color\",", "outputs: [\"resolved\", \"color\",");

/// Every lit scene, in every pipeline that resolves: the resolved HDR is finite and
/// within the half-float range everywhere, and not black.
#[test]
fn lit_scenes_are_finite_and_not_black() {
    let gpu = gpu();
    let pipelines = [
        "deferred_msaa_4x.ron",
        "deferred_msaa_4x_sample_mask.ron",
        "deferred_msaa_4x_tonemapped_resolve.ron",
        "deferred_per_sample_4x.ron",
        "deferred_msaa_4x_centroid.ron",
        "deferred_msaa_4x_coverage.ron",
    ];
    for pipeline in pipelines {
        for scene in [
            "builtin:spheres",
            "builtin:dense",
            "builtin:lights?count=64",
        ] {
            let frame = Render::new(pipeline, scene, SIZE)
                .edit(EXPORT_RESOLVED.0, EXPORT_RESOLVED.1)
                .run(&gpu);
            let hdr = frame.hdr(&gpu, "resolved");
            let bad = hdr
                .iter()
                .position(|p| p.iter().any(|c| !c.is_finite() || *c < 0.0 || *c > 65504.0));
            if let Some(i) = bad {
                let (x, y) = (i as u32 % SIZE.0, i as u32 / SIZE.0);
                panic!(
                    "{pipeline} {scene}: resolved pixel ({x}, {y}) is {:?}",
                    hdr[i]
                );
            }
            let lit = hdr.iter().filter(|p| p[0] + p[1] + p[2] > 0.01).count();
            assert!(
                lit > hdr.len() / 4,
                "{pipeline} {scene}: only {lit} of {} pixels have light",
                hdr.len()
            );
        }
    }
}

/// builtin:spheres without anti-aliasing renders, and its tone-mapped image is neither
/// black nor white on average.
#[test]
fn noaa_renders_the_spheres() {
    let gpu = gpu();
    let color = Render::new("deferred_noaa.ron", "builtin:spheres", SIZE)
        .read(&gpu, &["color"])
        .remove(0);
    let mean = color
        .pixels
        .iter()
        .map(|p| f64::from(p[0]) + f64::from(p[1]) + f64::from(p[2]))
        .sum::<f64>()
        / (3.0 * color.pixels.len() as f64);
    assert!(
        (20.0..230.0).contains(&mean),
        "mean channel value of the spheres without AA is {mean:.1}, expected 20..230"
    );
}
