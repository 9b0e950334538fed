//! Pipelines kept per device (rgraph-passes' kept.rs): a second graph on a device builds
//! none of the pipelines, layouts and shader modules the first built, and draws the same
//! image; a graph whose pass differs in a pipeline-overridable constant (the tone
//! mapping's exposure) builds its own pipeline and draws its own image.

use rgraph_core::gpu::{DeviceObjects, Gpu};

use crate::deferred_support::{gpu, Render};

const SIZE: (u32, u32) = (96, 64);
const PIPELINE: &str = "deferred_msaa_4x_tiled.ron";
const SCENE: &str = "builtin:dense";
/// The tone mapping pass's parameters in parts/tonemap.ron.
const TONEMAP_PARAMS: &str = "params: (operator: aces, exposure: 1.0),";

/// What rendering `render` created on `gpu`'s device (counted while its graph lives),
/// and its color.
fn render_counting(render: &Render<'_>, gpu: &Gpu) -> (DeviceObjects, Vec<[u8; 4]>) {
    let before = DeviceObjects::alive(&gpu.device);
    let frame = render.run(gpu);
    let created = DeviceObjects::alive(&gpu.device).minus(&before);
    (created, frame.image(gpu, "color").pixels)
}

#[test]
fn a_second_graph_on_a_device_builds_no_pipeline_and_draws_the_same_image() {
    let gpu = gpu();
    let render = Render::new(PIPELINE, SCENE, SIZE);
    let (_, first) = render_counting(&render, &gpu);
    // The first graph is dropped: only what the device keeps for every graph is alive.
    let (kept, second) = render_counting(&render, &gpu);
    assert_eq!(
        (
            kept.render_pipelines,
            kept.compute_pipelines,
            kept.shader_modules,
            kept.pipeline_layouts,
            kept.bind_group_layouts
        ),
        (0, 0, 0, 0, 0),
        "the second graph built objects again: {kept}"
    );
    assert!(first == second, "the second graph drew another image");
}

#[test]
fn a_pass_with_another_constant_builds_its_own_pipeline() {
    let gpu = gpu();
    let (_, plain) = render_counting(&Render::new(PIPELINE, SCENE, SIZE), &gpu);
    // The tone mapping pass exposes by its constant EXPOSURE: the WGSL stays the same.
    let brighter = Render::new(PIPELINE, SCENE, SIZE)
        .edit(TONEMAP_PARAMS, "params: (operator: aces, exposure: 2.0),");
    let (built, bright) = render_counting(&brighter, &gpu);
    assert!(
        built.render_pipelines > 0,
        "the tone mapping's EXPOSURE changed and no pipeline was built: {built}"
    );
    let sum = |p: &[u8; 4]| p[..3].iter().map(|&c| u32::from(c)).sum::<u32>();
    let brighter_pixels = (plain.iter().zip(&bright))
        .filter(|(a, b)| sum(b) > sum(a))
        .count();
    assert!(
        brighter_pixels > plain.len() / 4,
        "exposure 2 brightened {brighter_pixels} of {} pixels",
        plain.len()
    );
}
