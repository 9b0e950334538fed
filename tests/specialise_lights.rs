//! Specialisation to a lit scene without lights or ambient: pipelines/deferred_msaa_4x.ron
//! compiled for it drops the edge and light passes, deferred_msaa_4x_tiled.ron its tiled
//! pass, and both render the same image, the G-buffer's emission (GPU, lavapipe by
//! default).

use crate::deferred_support;

use deferred_support::measure::diff;
use deferred_support::{gpu, Render};
use rgraph_core::Features;
use rgraph_scene::analysis::Features as SceneFeatures;
use rgraph_scene::Scene;

const N: u32 = 64;

/// builtin:spheres without its lights and ambient, one material glowing so the image
/// is not black.
fn dark_spheres() -> Scene {
    let mut scene = Scene::load("builtin:spheres").expect("builtin:spheres loads");
    scene.lights.clear();
    scene.ambient = [0.0; 3];
    scene.materials[0].emissive_factor = [0.8, 0.5, 0.2];
    scene
}

#[test]
fn a_lit_scene_without_lights_drops_the_light_passes_and_renders_the_same() {
    drops_passes_and_renders_the_same(
        "deferred_msaa_4x.ron",
        &["edges", "shadow maps", "light edges", "light the rest"],
    );
}

/// The tiled pipeline drops its compute pass, and a plain resolve of the G-buffer's HDR
/// stands in for it.
#[test]
fn a_lit_scene_without_lights_drops_the_tiled_pass_and_renders_the_same() {
    drops_passes_and_renders_the_same(
        "deferred_msaa_4x_tiled.ron",
        &["shadow maps", "light tiled"],
    );
}

fn drops_passes_and_renders_the_same(pipeline: &str, dropped: &[&str]) {
    let gpu = gpu();
    let scene = dark_spheres();
    let features = SceneFeatures::of(&scene).names();
    assert_eq!(
        features.to_string(),
        "emissive, lit, no_lights, shallow_depth"
    );
    let render = |features: Features| {
        let frame = Render::new(pipeline, "dark spheres", (N, N))
            .with_scene(scene.clone())
            .features(features)
            .run(&gpu);
        let passes: Vec<String> = frame.plan().passes.iter().map(|p| p.name.clone()).collect();
        (passes, frame.image(&gpu, "color"))
    };
    let (general_passes, general) = render(SceneFeatures::general().names());
    let (special_passes, special) = render(features);
    for pass in dropped {
        assert!(
            general_passes.iter().any(|p| p == pass),
            "{pipeline}: {pass}"
        );
        assert!(
            !special_passes.iter().any(|p| p == pass),
            "{pipeline}: {pass}"
        );
    }
    let worst = diff(&general, &special, None).max;
    assert!(worst <= 1, "a channel differs by {worst}/255");
    let glowing = special.pixels.iter().filter(|p| p[0] > 0).count();
    assert!(glowing > 100, "only {glowing} pixels glow");
    println!(
        "{pipeline}: spheres without lights at {N}x{N}: {} instead of {} passes, worst difference \
         {worst}/255, identical: {}",
        special_passes.len(),
        general_passes.len(),
        general.pixels == special.pixels
    );
}
