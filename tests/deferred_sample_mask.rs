//! `light_edge` shades edge samples two ways, and they must agree: `sample_index` runs
//! the fragment shader per sample; `sample_mask` draws once per sample with the
//! pipeline's multisample mask (DX10.0's method). Both read the same G-buffer sample and
//! reconstruct positions at the pixel center, so the lit HDR is bit-identical.

use crate::deferred_support;

use deferred_support::{gpu, Render};

const SIZE: (u32, u32) = (64, 64);
const RED: [u8; 4] = [255, 0, 0, 255];

/// Also exports the resolved HDR target, to compare before tone mapping.
const EXPORT_RESOLVED: (&str, &str) =
    ("outputs: [\"color\",", "outputs: [\"resolved\", \"color\",");

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
                .edit(EXPORT_RESOLVED.0, EXPORT_RESOLVED.1)
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
        let differing: Vec<String> = by_index
            .iter()
            .zip(&by_mask)
            .enumerate()
            .filter(|(_, (a, b))| a != b)
            .map(|(i, (a, b))| {
                let (x, y) = (i as u32 % SIZE.0, i as u32 / SIZE.0);
                format!("({x}, {y}): sample_index {a:?}, sample_mask {b:?}")
            })
            .collect();
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
