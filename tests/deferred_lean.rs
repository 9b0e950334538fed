//! The lean G-buffer (pipelines/deferred_msaa_4x_lean.ron): albedo, normal, material and a
//! stencil-less depth32float, 16 bytes per sample (20 with RGB9E5 emission), renders the
//! tiled pipeline's 32-byte G-buffer image within 1/255, and its layout errors are clear.

use rgraph_scene::Scene;

use crate::baselines_errors::{assert_names, error};
use crate::deferred_support;
use deferred_support::{gpu, unchanged, Render};

const LEAN: &str = "deferred_msaa_4x_lean.ron";
const TILED: &str = "deferred_msaa_4x_tiled.ron";

/// Where the lean and the full G-buffer differ, the compare detector found an edge in one
/// and not the other: the lean G-buffer's samples have their own depths along a slope,
/// the full one's the fragment's centroid depth, so a surface steep enough to change depth
/// by 1% within a pixel is an edge only in the lean one (and shaded per sample). That takes
/// a steeper surface the smaller the pixels: at 192x108, 3% of the 64-lights scene
/// differs, so the test renders at 480x270.
fn agreement(scene: &str, edit: fn(&mut Scene)) -> f64 {
    deferred_support::agreement((LEAN, TILED), scene, edit, (480, 270))
}

/// Every material glows, in HDR: the lean G-buffer's emission channel (RGB9E5) carries it.
fn glowing(scene: &mut Scene) {
    for (i, m) in scene.materials.iter_mut().enumerate() {
        m.emissive_factor = [0.9, 0.4 * (i % 3) as f32, 0.1];
        m.emissive_strength = 3.0;
    }
}

/// One material unlit, one emissive, the rest lit: all three ways a sample emits.
fn mixed(scene: &mut Scene) {
    scene.materials[0].unlit = true;
    scene.materials[1].emissive_factor = [0.2, 0.7, 1.0];
}

#[test]
fn the_lean_gbuffer_renders_the_full_ones_image_within_one_level() {
    for (scene, edit, name) in [
        ("builtin:spheres", unchanged as fn(&mut Scene), "spheres"),
        ("builtin:dense", unchanged, "dense"),
        ("builtin:lights?count=64", unchanged, "64 lights"),
        ("builtin:unlit", unchanged, "unlit"),
        ("builtin:spheres", glowing, "glowing spheres"),
        ("builtin:dense", mixed, "dense, unlit and emissive"),
    ] {
        let share = agreement(scene, edit);
        eprintln!("{name}: {:.4}% within 1/255", share * 100.0);
        assert!(share >= 0.99, "{name}: only {share} of pixels within 1/255");
    }
}

#[test]
fn the_lean_gbuffer_stores_16_bytes_per_sample_and_20_with_emission() {
    let gpu = gpu();
    let stored = |features: &[&str]| {
        let frame = Render::new(LEAN, "builtin:spheres", (64, 48))
            .features(features.iter().copied().collect())
            .run(&gpu);
        let pass = frame
            .plan()
            .passes
            .iter()
            .find(|p| p.name.starts_with("gbuffer"))
            .unwrap()
            .clone();
        (pass.name, pass.stored_bytes_per_sample)
    };
    assert_eq!(stored(&[]), ("gbuffer".into(), 16));
    assert_eq!(stored(&["emissive"]), ("gbuffer (emissive)".into(), 20));
    // The full G-buffer: albedo 4, normal 4, material 4, view depth 4, HDR 8, D32S8 8.
    let full = Render::new(TILED, "builtin:spheres", (64, 48)).run(&gpu);
    let gbuffer = full
        .plan()
        .passes
        .iter()
        .find(|p| p.name == "gbuffer")
        .unwrap();
    assert_eq!(gbuffer.stored_bytes_per_sample, 32);
}

/// The layout is read from the slots a file binds; contradictions are load errors
/// naming the pass.
#[test]
fn contradicting_layouts_are_errors_naming_the_pass() {
    let tiled_inputs = "\"emission\": \"emission\", \"depth\": \"depth\", \"shadows\"";
    let message = error(
        LEAN,
        tiled_inputs,
        &tiled_inputs.replace(
            "\"depth\": \"depth\",",
            "\"hdr\": \"albedo\", \"depth\": \"depth\",",
        ),
    );
    assert_names(
        &message,
        &["light tiled (emissive)", "\"hdr\" and \"emission\" both"],
    );

    let message = error(
        LEAN,
        "when: \"emissive\",\n            params: (edges: (detector: compare)),",
        &"when: \"emissive\",\n            params: (edges: (detector: compare)),"
            .replace("compare)", "compare), background: (0.1, 0.2, 0.3)"),
    );
    assert_names(
        &message,
        &[
            "light tiled (emissive)",
            "background is for a G-buffer without",
        ],
    );

    let message = error(
        LEAN,
        "params: (edges: (detector: compare)),\n            inputs: {\n                \"albedo\": \"albedo\", \"normal\": \"normal\", \"material\": \"material\", \"depth\"",
        "params: (edges: (detector: compare), background: (1.0, -1.0, 0.0)),\n            inputs: {\n                \"albedo\": \"albedo\", \"normal\": \"normal\", \"material\": \"material\", \"depth\"",
    );
    assert_names(
        &message,
        &["light tiled", "background must be finite and not negative"],
    );
}
