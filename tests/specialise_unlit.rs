//! Specialisation to an unlit-only scene: pipelines/deferred_msaa_4x.ron compiled for
//! builtin:unlit's features drops the normal and material channels, the edge pass and
//! the light passes, and renders the same image, as do the other deferred pipelines
//! that specialise (GPU, lavapipe by default).

use crate::deferred_support;

use deferred_support::measure::diff;
use deferred_support::{gpu, Render};
use rgraph_core::file::{load_file, Registry};
use rgraph_core::{CompileOptions, Features, Plan, PlanCache};
use rgraph_scene::analysis::Features as SceneFeatures;
use rgraph_scene::glam::DVec3;
use rgraph_scene::Scene;

const PIPELINE: &str = "deferred_msaa_4x.ron";
const N: u32 = 64;

fn unlit() -> Scene {
    Scene::load("builtin:unlit").expect("builtin:unlit loads")
}

/// The pipeline's plan for `features` with only "color" kept, as `rgraph render` runs
/// it: the debug views are culled.
fn plan(features: &Features) -> Plan {
    let registry = {
        let mut r = Registry::with_builtins();
        rgraph_passes::register(&mut r, None);
        r
    };
    let path = format!("{}/pipelines/{PIPELINE}", env!("CARGO_MANIFEST_DIR"));
    let mut loaded = load_file(&path, &registry).unwrap_or_else(|e| panic!("{e}"));
    loaded.keep_outputs(&["color"]).expect("color is an output");
    let options = CompileOptions {
        output_size: (N, N),
        ..CompileOptions::default()
    };
    loaded
        .compile_for(&options, features)
        .unwrap_or_else(|e| panic!("{e}"))
}

fn names(plan: &Plan) -> Vec<&str> {
    plan.passes.iter().map(|p| p.name.as_str()).collect()
}

#[test]
fn an_unlit_scene_drops_lighting_and_its_g_buffer_channels() {
    let features = SceneFeatures::of(&unlit()).names();
    let general = plan(&SceneFeatures::general().names());
    let special = plan(&features);
    assert_eq!(
        names(&general),
        [
            "gbuffer",
            "edges",
            "shadow maps",
            "light edges",
            "light the rest",
            "resolve",
            "transparent",
            "composite transparent",
            "points lines",
            "composite points lines",
            "tonemap"
        ]
    );
    assert_eq!(names(&special), ["gbuffer (unlit)", "resolve", "tonemap"]);
    let dropped: Vec<(&str, &str)> = special
        .culled
        .iter()
        .filter(|c| c.dropped)
        .map(|c| (c.name.as_str(), c.reason.as_str()))
        .collect();
    let not_lit = r#"condition "!unlit_only" is false"#;
    // builtin:unlit has no lights either.
    let no_light = r#"condition "!unlit_only & !no_lights" is false ("unlit_only" is set, "no_lights" is set)"#;
    // The shadow maps too (no light casts a shadow either).
    let no_shadow = r#"condition "!unlit_only & !no_lights & shadows" is false ("unlit_only" is set, "no_lights" is set, "shadows" is not set)"#;
    // Nor BLEND materials.
    let no_blend = r#"condition "blend" is false"#;
    // Nor a background (no environment, no --background).
    let no_background = r#"condition "background" is false"#;
    // And a fixed exposure, as every render without --exposure auto.
    let fixed = r#"condition "auto_exposure" is false"#;
    let no_points_lines = r#"condition "points_lines" is false"#;
    assert_eq!(
        dropped,
        [
            ("gbuffer", not_lit),
            ("edges", no_light),
            ("shadow maps", no_shadow),
            ("light edges", no_light),
            ("light the rest", no_light),
            ("background", no_background),
            ("transparent", no_blend),
            ("composite transparent", no_blend),
            ("points lines", no_points_lines),
            ("composite points lines", no_points_lines),
            ("auto exposure", fixed),
            ("tonemap (auto exposure)", fixed),
            ("debug normals", not_lit),
            ("debug lights", not_lit),
            ("debug shadows", no_shadow),
            ("debug cascades", no_shadow),
        ]
    );
    for channel in ["normal", "material"] {
        let resource = special.find(channel).unwrap();
        assert_eq!(resource.culled.as_deref(), Some(not_lit), "{channel}");
        assert_eq!(resource.physical, None, "{channel}");
    }
    // The G-buffer shrinks from 32 to 20 bytes per sample (normal 4 and material 4 in
    // memory, 8 and 4 in wgpu's attachment accounting), and the general plan's shadow
    // atlas (4096 x 4096 depth32float) is not made.
    assert_eq!(special.passes[0].color_bytes_per_sample, 20);
    let saved = general.memory.physical_bytes - special.memory.physical_bytes;
    assert_eq!(saved, u64::from(N * N) * 4 * (4 + 4) + 4096 * 4096 * 4);
    println!(
        "builtin:unlit at {N}x{N}: {} of {} passes, {} of {} bytes",
        special.passes.len(),
        general.passes.len(),
        special.memory.physical_bytes,
        general.memory.physical_bytes
    );
}

/// The deferred pipelines that specialise to unlit-only scenes as this one does.
const SPECIALISED: [&str; 8] = [
    "deferred_msaa_4x.ron",
    "deferred_msaa_4x_centroid.ron",
    "deferred_msaa_4x_coverage.ron",
    "deferred_msaa_4x_sample_mask.ron",
    "deferred_msaa_4x_tonemapped_resolve.ron",
    "deferred_noaa.ron",
    "deferred_onthefly_resolve_4x.ron",
    "deferred_per_sample_4x.ron",
];

/// The image is what the light passes would have left: they skip unlit pixels.
#[test]
fn the_specialised_unlit_image_equals_the_unspecialised_one() {
    let gpu = gpu();
    for pipeline in SPECIALISED {
        let render = |features: Features| {
            let frame = Render::new(pipeline, "builtin:unlit", (N, N))
                .features(features)
                .run(&gpu);
            (frame.plan().passes.len(), frame.image(&gpu, "color"))
        };
        let (general_passes, general) = render(SceneFeatures::general().names());
        let (special_passes, special) = render(SceneFeatures::of(&unlit()).names());
        assert!(special_passes < general_passes, "{pipeline}");
        let worst = diff(&general, &special, None).max;
        assert!(worst <= 1, "{pipeline}: a channel differs by {worst}/255");
        // Not a blank frame: the shapes cover about a fifth of it.
        let drawn = special.pixels.len() - special.count([0, 0, 0, 255]);
        assert!(
            drawn > special.pixels.len() / 10,
            "{pipeline}: {drawn} pixels drawn"
        );
        println!(
            "{pipeline} on builtin:unlit at {N}x{N}: {special_passes} instead of \
             {general_passes} passes, worst difference {worst}/255, identical: {}",
            general.pixels == special.pixels
        );
    }
}

#[test]
fn a_second_scene_with_the_same_features_reuses_the_plan() {
    let registry = {
        let mut r = Registry::with_builtins();
        rgraph_passes::register(&mut r, None);
        r
    };
    let path = format!("{}/pipelines/{PIPELINE}", env!("CARGO_MANIFEST_DIR"));
    let loaded = load_file(&path, &registry).unwrap_or_else(|e| panic!("{e}"));
    let options = CompileOptions::default();
    let mut cache = PlanCache::new();
    let first = unlit();
    let mut second = unlit();
    second.camera.position += DVec3::new(0.25, 0.0, 5.0);
    second.materials[0].base_color_factor = [0.2, 0.4, 0.6, 1.0];
    let spheres = Scene::load("builtin:spheres").unwrap();
    for scene in [&first, &second, &spheres, &first] {
        let features = SceneFeatures::of(scene).names();
        cache
            .get_or_compile(&loaded, &options, &features)
            .unwrap_or_else(|e| panic!("{e}"));
    }
    // builtin:unlit compiles, its edit hits, builtin:spheres compiles, builtin:unlit hits.
    assert_eq!((cache.misses(), cache.hits()), (2, 2));
}
