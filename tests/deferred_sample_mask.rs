//! `light_edge` shades edge samples two ways, and they must agree: `sample_index` runs
//! the fragment shader per sample; `sample_mask` draws once per sample with the
//! pipeline's multisample mask (DX10.0's method). Both read the same G-buffer sample and
//! reconstruct positions at the pixel center, so the lit HDR is bit-identical.

use crate::deferred_support;

use deferred_support::{gpu, hdr_differences, Render};

const SIZE: (u32, u32) = (64, 64);
const RED: [u8; 4] = [255, 0, 0, 255];

/// Also exports the resolved HDR target, to compare before tone mapping.

#[test]
fn sample_mask_and_sample_index_light_edges_identically() {
    let gpu = gpu();
    for scene in [
        "builtin:dense",
        "builtin:spheres",
        "builtin:lights?count=40",
    ] {
        let render = |pipeline| {
            let frame = Render::new(pipeline, scene, SIZE)
                .export_resolved()
                .run(&gpu);
            let edges = frame.image(&gpu, "debug.edges").count(RED);
            (frame.hdr(&gpu, "resolved"), edges)
        };
        let (by_index, edges) = render("deferred_msaa_4x.ron");
        let (by_mask, _) = render("deferred_msaa_4x_sample_mask.ron");
        assert!(
            edges > 20,
            "{scene}: only {edges} edge pixels, the comparison proves little"
        );
        let differing =
            hdr_differences(&by_index, &by_mask, SIZE.0, ("sample_index", "sample_mask"));
        assert!(
            differing.is_empty(),
            "{scene}: {} of {} resolved pixels differ ({edges} edge pixels), e.g.:\n{}",
            differing.len(),
            by_index.len(),
            differing
                .iter()
                .take(10)
                .cloned()
                .collect::<Vec<_>>()
                .join("\n")
        );
    }
}
