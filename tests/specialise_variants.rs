//! Shader variants (rgraph-passes, passes/src/variant.rs): the G-buffer, light and
//! forward shaders compiled for only the scene's features render exactly what the general
//! shaders render (GPU, lavapipe by default), and which variants a plan builds is known
//! without a GPU.

use crate::deferred_support;

use deferred_support::{gpu, Render};
use rgraph_core::file::{load_file, LoadedGraph, Registry};
use rgraph_core::CompileOptions;
use rgraph_passes::variant::{shader_variants, GatedShader, Variant, Variants};
use rgraph_scene::analysis::Features as SceneFeatures;
use rgraph_scene::Scene;

const SIZE: (u32, u32) = (64, 64);
const GLTF: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/scene/tests/fixtures/hierarchy_embedded.gltf"
);
/// Each lacks something some gated shader has code for: spheres spot lights, lights
/// (7 point + 1 spot) directional lights, unlit every light, the glTF fixture (an
/// emissive, masked, double-sided triangle) lights and textures; none has textures.
const SCENES: [&str; 4] = [
    "builtin:spheres",
    "builtin:lights?count=8",
    "builtin:unlit",
    GLTF,
];
const PIPELINES: [&str; 3] = [
    "deferred_msaa_4x.ron",
    "deferred_msaa_4x_tiled.ron",
    "forward_msaa_4x.ron",
];

fn features(scene: &str) -> SceneFeatures {
    let scene = Scene::load(scene).unwrap_or_else(|e| panic!("{scene}: {e}"));
    SceneFeatures::of(&scene)
}

/// The resolved HDR target's bits and the color image, rendered with the plan for the
/// scene's features and shaders compiled as `variants` says. The resolved target shows
/// any difference before tone mapping and 8-bit rounding could hide it.
fn render(pipeline: &str, scene: &str, variants: Variants) -> (Vec<[u32; 4]>, Vec<[u8; 4]>) {
    let gpu = gpu();
    let frame = Render::new(pipeline, scene, SIZE)
        .export_resolved()
        .features(features(scene).names())
        .variants(variants)
        .run(&gpu);
    let hdr = frame
        .hdr(&gpu, "resolved")
        .iter()
        .map(|p| p.map(f32::to_bits))
        .collect();
    (hdr, frame.image(&gpu, "color").pixels)
}

#[test]
fn the_scene_s_variants_render_the_general_variants_image_bit_for_bit() {
    for pipeline in PIPELINES {
        for scene in SCENES {
            let (special_hdr, special) = render(pipeline, scene, Variants::Scene);
            let (general_hdr, general) = render(pipeline, scene, Variants::General);
            assert!(
                special_hdr == general_hdr,
                "{pipeline} on {scene}: the resolved HDR differs"
            );
            assert!(
                special == general,
                "{pipeline} on {scene}: the color differs"
            );
            // Not a blank frame.
            let drawn = special.iter().filter(|p| p[..3] != [0, 0, 0]).count();
            assert!(
                drawn > special.len() / 20,
                "{pipeline} on {scene}: {drawn} pixels drawn"
            );
            println!(
                "{pipeline} on {scene}: identical, with {}",
                variants(pipeline, scene).join("; ")
            );
        }
    }
}

/// Every scene compiles out something: the comparison above tests gated code.
#[test]
fn every_scene_tested_lacks_some_gated_feature() {
    for scene in SCENES {
        let features = features(scene);
        let special = [
            GatedShader::GBuffer,
            GatedShader::Light,
            GatedShader::Forward,
        ]
        .into_iter()
        .filter(|&s| !Variant::of(s, &features).is_general())
        .count();
        assert_eq!(special, 3, "{scene}");
    }
}

fn loaded(pipeline: &str) -> LoadedGraph {
    let mut registry = Registry::with_builtins();
    rgraph_passes::register(&mut registry, None);
    let path = format!("{}/pipelines/{pipeline}", env!("CARGO_MANIFEST_DIR"));
    load_file(&path, &registry).unwrap_or_else(|e| panic!("{e}"))
}

/// The variants `pipeline` builds for `scene`, as `rgraph explain` lists them:
/// `shader {features}: passes`.
fn variants(pipeline: &str, scene: &str) -> Vec<String> {
    let loaded = loaded(pipeline);
    let features = features(scene);
    let options = CompileOptions {
        output_size: SIZE,
        ..CompileOptions::default()
    };
    let plan = loaded
        .compile_for(&options, &features.names())
        .unwrap_or_else(|e| panic!("{e}"));
    let passes: Vec<(&str, &str)> = plan
        .passes
        .iter()
        .map(|p| {
            (
                p.name.as_str(),
                loaded.plugin(&p.name).expect("a file pass"),
            )
        })
        .collect();
    shader_variants(&features, &passes)
        .iter()
        .map(|v| format!("{}: {}", v.variant, v.passes.join(", ")))
        .collect()
}

#[test]
fn each_builtin_scene_s_variants() {
    let light = "light edges, light the rest";
    let expected: [(&str, [&str; 2], &str); 4] = [
        (
            "builtin:spheres",
            [
                "gbuffer.wgsl {}: gbuffer",
                "light.wgsl {directional_lights, point_lights}",
            ],
            "forward.wgsl {directional_lights, point_lights}: forward",
        ),
        (
            "builtin:dense",
            [
                "gbuffer.wgsl {double_sided}: gbuffer",
                "light.wgsl {point_lights, spot_lights}",
            ],
            "forward.wgsl {point_lights, spot_lights, double_sided}: forward",
        ),
        (
            "builtin:lights",
            [
                "gbuffer.wgsl {}: gbuffer",
                "light.wgsl {point_lights, spot_lights}",
            ],
            "forward.wgsl {point_lights, spot_lights}: forward",
        ),
        (
            // No lights: the light passes are dropped, and the unlit G-buffer pass runs.
            "builtin:unlit",
            ["gbuffer.wgsl {double_sided}: gbuffer (unlit)", ""],
            "forward.wgsl {double_sided}: forward",
        ),
    ];
    for (scene, [gbuffer, lighting], forward) in expected {
        let mut deferred = vec![gbuffer.to_owned()];
        if !lighting.is_empty() {
            // Every lit built-in scene has shadows: the shadows and cascades views take
            // the tiled pass's shader, specialised as the light passes' is.
            let views = lighting.replace("light.wgsl", "light_tiled.wgsl");
            deferred.push(format!("{views}: debug shadows, debug cascades"));
            deferred.push(format!("{lighting}: {light}"));
        }
        assert_eq!(variants("deferred_msaa_4x.ron", scene), deferred, "{scene}");
        // Forward's shadow views are its own pass with the scene's variant.
        let forward = match lighting.is_empty() {
            true => forward.to_owned(),
            false => format!("{forward}, debug shadows, debug cascades"),
        };
        assert_eq!(variants("forward_msaa_4x.ron", scene), [forward], "{scene}");
    }
}

/// Explain finds each pass's shader through the plugin its file names.
#[test]
fn a_loaded_file_names_each_pass_s_plugin() {
    let loaded = loaded("deferred_msaa_4x.ron");
    assert_eq!(loaded.plugin("light edges"), Some("light_edge"));
    assert_eq!(loaded.plugin("debug lights"), Some("debug_view"));
    assert_eq!(loaded.plugin("no such pass"), None);
}
