//! The edge passes vanish at one sample per pixel: the 4x deferred pipelines rewritten to
//! 1x (as `bench --sweep samples` does) omit `edge_stencil` and `light_edge`, say why,
//! and render what the 1x pipeline without edge passes renders (GPU, lavapipe by
//! default).

use crate::deferred_support;
use crate::deferred_support::measure;

use deferred_support::{gpu, Render};
use measure::diff;

const N: u32 = 64;
const SCENE: &str = "builtin:spheres";
const OMITTED: &str = "one sample per pixel: a pixel holds one surface, so there are no edge \
                       pixels to find or to shade per sample";

#[test]
fn the_edge_passes_are_omitted_at_one_sample_and_the_image_is_the_no_aa_one() {
    let gpu = gpu();
    let noaa = Render::new("deferred_noaa.ron", SCENE, (N, N))
        .run(&gpu)
        .image(&gpu, "color");
    // compare marks edges where samples differ; all marks every pixel (per-sample
    // shading everywhere): at one sample both leave the lighting to light_nonedge.
    for pipeline in ["deferred_msaa_4x.ron", "deferred_per_sample_4x.ron"] {
        let frame = Render::new(pipeline, SCENE, (N, N))
            .param("msaa", 1)
            .run(&gpu);
        let plan = frame.plan();
        let live: Vec<&str> = plan
            .passes
            .iter()
            .map(|p| p.name.as_str())
            .filter(|name| !name.starts_with("debug "))
            .collect();
        assert_eq!(
            live,
            ["gbuffer", "light the rest", "resolve", "tonemap"],
            "{pipeline}"
        );
        let omitted: Vec<(&str, &str)> = plan
            .culled
            .iter()
            .filter(|c| c.reason == OMITTED)
            .map(|c| (c.name.as_str(), c.reason.as_str()))
            .collect();
        assert_eq!(
            omitted,
            [("edges", OMITTED), ("light edges", OMITTED)],
            "{pipeline}"
        );
        let image = frame.image(&gpu, "color");
        let d = diff(&image, &noaa, None);
        // The same lighting pass, and the resolve of one sample is a copy: bit-identical.
        assert_eq!(d.max, 0, "{pipeline}: {d}");
        println!("{pipeline} at 1x vs deferred_noaa on {SCENE} at {N}x{N}: {d}");
    }
}
