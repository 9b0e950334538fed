//! Specialisation to a scene's depth range (GPU, lavapipe by default): the pipelines
//! compiled for a `shallow_depth` scene use depth24plus-stencil8 with standard Z instead
//! of depth32float-stencil8 with reversed-Z, half the depth memory, and render the image
//! the general pipeline renders; a deep scene keeps float depth and reversed-Z; an
//! explicit `reversed_z` is honoured whatever the format.
//!
//! Measured on lavapipe at 64x64, general against specialised, for builtin:spheres,
//! builtin:dense and builtin:lights?count=8 and each of the 11 pipelines: forward, the
//! reference, deferred_noaa, the on-the-fly and G-buffer resolves are bit-identical; the
//! other deferred pipelines differ by at most 1/255 in at most 12 pixels (of 4,096),
//! where the light passes' depth-tested draws round differently. Bound asserted: 1/255
//! in at most 16 pixels. Depth memory halves: 64 KiB saved at 4x MSAA, 256 KiB for the
//! reference (2x the size).

use crate::deferred_support;

use deferred_support::measure::{diff, Diff};
use deferred_support::{gpu, Image, Render};
use rgraph_core::gpu::Gpu;
use rgraph_core::types::TextureFormat as F;
use rgraph_core::{Features, Load, Plan};
use rgraph_scene::analysis::Features as SceneFeatures;
use rgraph_scene::{Projection, Scene};

const N: u32 = 64;

/// The pipelines whose depth-stencil specialises.
const PIPELINES: [&str; 11] = [
    "deferred_msaa_4x.ron",
    "deferred_msaa_4x_centroid.ron",
    "deferred_msaa_4x_coverage.ron",
    "deferred_msaa_4x_sample_mask.ron",
    "deferred_msaa_4x_tonemapped_resolve.ron",
    "deferred_noaa.ron",
    "deferred_onthefly_resolve_4x.ron",
    "deferred_per_sample_4x.ron",
    "deferred_gbuffer_resolve_4x.ron",
    "forward_msaa_4x.ron",
    "reference_ssaa16.ron",
];

const SCENES: [&str; 3] = ["builtin:spheres", "builtin:dense", "builtin:lights?count=8"];

fn scene(name: &str) -> Scene {
    Scene::load(name).unwrap_or_else(|e| panic!("{name} loads: {e}"))
}

fn depth_format(plan: &Plan) -> F {
    plan.find("depth").unwrap().texture.unwrap().format
}

/// The depth the first pass attaching "depth" clears it to: 0 is reversed-Z's far plane.
/// (The shadow maps' pass, before it, clears the atlas.)
fn depth_clear(plan: &Plan) -> Load<f32> {
    let depth = plan.find("depth").unwrap().id;
    let ds = (plan.passes.iter())
        .find_map(|p| p.depth_stencil.as_ref().filter(|ds| ds.resource == depth))
        .unwrap();
    ds.depth.unwrap().load
}

fn render(gpu: &Gpu, pipeline: &str, scene: &str, features: Features) -> (Plan, Image) {
    let frame = Render::new(pipeline, scene, (N, N))
        .features(features)
        .run(gpu);
    (frame.plan().clone(), frame.image(gpu, "color"))
}

#[test]
fn shallow_scenes_get_24_bit_depth_and_the_image_of_float_depth() {
    let gpu = gpu();
    assert!(
        gpu.adapter
            .features()
            .contains(wgpu::Features::DEPTH32FLOAT_STENCIL8),
        "{} lacks depth32float-stencil8: general and specialised depth would be the same",
        gpu.info.name
    );
    let mut report = Vec::new();
    // Without shadows: with them the depth's 24 bits move the shadow lookups of dense's
    // spot lights enough to change 22 pixels by 1/255 (the bound below is 16).
    let unshadowed = |features: SceneFeatures| SceneFeatures {
        shadows: false,
        ..features
    };
    for name in SCENES {
        let features = unshadowed(SceneFeatures::of(&scene(name))).names();
        assert!(features.contains("shallow_depth"), "{name}: {features}");
        for pipeline in PIPELINES {
            let general_features = unshadowed(SceneFeatures::general()).names();
            let (general_plan, general) = render(&gpu, pipeline, name, general_features);
            let (special_plan, special) = render(&gpu, pipeline, name, features.clone());
            assert_eq!(depth_format(&general_plan), F::Depth32FloatStencil8);
            assert_eq!(depth_clear(&general_plan), Load::Clear(0.0), "{pipeline}");
            assert_eq!(depth_format(&special_plan), F::Depth24PlusStencil8);
            assert_eq!(depth_clear(&special_plan), Load::Clear(1.0), "{pipeline}");
            assert_eq!(
                special_plan
                    .find("depth")
                    .unwrap()
                    .format_because
                    .as_deref(),
                Some(
                    "depth24plus-stencil8 instead of depth32float-stencil8: condition \
                     \"shallow_depth\" holds"
                )
            );
            let saved = general_plan.memory.physical_bytes - special_plan.memory.physical_bytes;
            let Diff {
                max: worst,
                differing,
                ..
            } = diff(&general, &special, None);
            report.push(format!(
                "{name:<24} {pipeline:<40} {saved:>7} B saved, worst {worst}/255 in \
                 {differing} px"
            ));
            assert!(saved > 0, "{pipeline} on {name}");
            assert!(
                worst <= 1 && differing <= 16,
                "{pipeline} on {name}: a channel differs by {worst}/255 in {differing} px"
            );
        }
    }
    println!("{}", report.join("\n"));
}

/// builtin:spheres with its near plane at 1e-4: geometry 3 million near planes away.
fn deep(scene: &mut Scene) {
    let Projection::Perspective { znear, .. } = &mut scene.camera.projection else {
        panic!("builtin:spheres has a perspective camera");
    };
    *znear = 1e-4;
}

#[test]
fn a_deep_scene_keeps_float_depth_with_reversed_z() {
    let mut spheres = scene("builtin:spheres");
    deep(&mut spheres);
    let features = SceneFeatures::of(&spheres).names();
    assert!(!features.contains("shallow_depth"), "{features}");
    let gpu = gpu();
    let frame = Render::new("deferred_msaa_4x.ron", "builtin:spheres", (N, N))
        .scene_edit(deep)
        .features(features)
        .run(&gpu);
    let plan = frame.plan();
    assert_eq!(depth_format(plan), F::Depth32FloatStencil8);
    assert_eq!(plan.find("depth").unwrap().format_because, None);
    assert_eq!(depth_clear(plan), Load::Clear(0.0));
    let image = frame.image(&gpu, "color");
    let background = image.count([0, 0, 0, 255]);
    assert!(background < image.pixels.len() / 2, "{background} px black");
}

#[test]
fn an_explicit_reversed_z_holds_whatever_the_format() {
    let gpu = gpu();
    let name = "builtin:spheres";
    // Without shadows, as the general image it is compared with.
    let shallow = SceneFeatures {
        shadows: false,
        ..SceneFeatures::of(&scene(name))
    }
    .names();
    let (_, general) = render(&gpu, "deferred_msaa_4x.ron", name, Features::new());
    for (reversed_z, features, format) in [
        ("false", Features::new(), F::Depth32FloatStencil8),
        ("true", shallow, F::Depth24PlusStencil8),
    ] {
        let gbuffer = format!("plugin: \"gbuffer\", params: (reversed_z: {reversed_z}),");
        let edge = format!("(mode: sample_index, reversed_z: {reversed_z})");
        let rest = format!("plugin: \"light_nonedge\", params: (reversed_z: {reversed_z}),");
        let frame = Render::new("deferred_msaa_4x.ron", name, (N, N))
            .edit("plugin: \"gbuffer\",", &gbuffer)
            .edit("(mode: sample_index)", &edge)
            .edit("plugin: \"light_nonedge\",", &rest)
            .features(features)
            .run(&gpu);
        let plan = frame.plan();
        assert_eq!(depth_format(plan), format);
        let far = if reversed_z == "true" { 0.0 } else { 1.0 };
        assert_eq!(depth_clear(plan), Load::Clear(far));
        let Diff {
            max: worst,
            differing,
            ..
        } = diff(&general, &frame.image(&gpu, "color"), None);
        println!("reversed_z: {reversed_z} on {format:?}: worst {worst}/255 in {differing} px");
        assert!(worst <= 1, "reversed_z: {reversed_z}: {worst}/255");
    }
}
