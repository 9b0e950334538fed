//! `rgraph explain --scene`: the plan specialised to a scene, what it drops and why, the
//! depth format it picks, the memory it saves against the plan for a scene using every
//! feature, and the shader variants it builds. No GPU, but for one `--profile adapter`
//! (lavapipe's formats).

use std::process::{Command, Output};

fn rgraph(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rgraph"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("the rgraph binary runs")
}

fn explain(scene: &str, format: &str) -> (Option<i32>, String, String) {
    explain_on(scene, format, "webgpu")
}

/// As on a device with `profile` (`webgpu` or `adapter`).
fn explain_on(scene: &str, format: &str, profile: &str) -> (Option<i32>, String, String) {
    let out = rgraph(&[
        "explain",
        "--pipeline",
        "pipelines/deferred_msaa_4x.ron",
        "--scene",
        scene,
        "--size",
        "64x64",
        "--format",
        format,
        "--profile",
        profile,
    ]);
    let text = |b: &[u8]| String::from_utf8_lossy(b).into_owned();
    (out.status.code(), text(&out.stdout), text(&out.stderr))
}

#[test]
fn an_unlit_scene_s_plan_says_what_it_drops_and_saves() {
    let (code, stdout, stderr) = explain("builtin:unlit", "text");
    assert_eq!(code, Some(0), "{stderr}");
    for expected in [
        "scene builtin:unlit: features double_sided, no_lights, shallow_depth, unlit, unlit_only\n",
        "depth 9.500 .. 10.500 (far/near 1.1); smallest edge 12.80 px at 64x64 (yellow tilted square)",
        "features: no_lights, shallow_depth, unlit_only\n",
        "    0. gbuffer (unlit) (render)",
        "dropped passes:\n  - gbuffer: condition \"!unlit_only\" is false\n",
        "against the plan for a scene using every feature (features: blend, clearcoat, \
         clearcoat_normal, points_lines, shadows, sheen, specular):\n  passes: 6 instead of 18\n",
        "    - light edges: condition \"!unlit_only & !no_lights\" is false (\"unlit_only\" is set, \"no_lights\" is set)\n",
        "    not allocated: normal (64.0 KiB): condition \"!unlit_only\" is false\n",
        // The general plan draws shadow maps into a 64 MiB atlas; an unlit scene none.
        "  memory: 416.0 KiB physical instead of 64.8 MiB (64.4 MiB saved, 99%)\n",
    ] {
        assert!(stdout.contains(expected), "no {expected:?} in:\n{stdout}");
    }
}

/// A lit scene without BLEND materials keeps the general plan but for the transparent
/// passes and their accumulation target.
#[test]
fn a_lit_scene_keeps_the_general_plan_but_the_transparent_passes() {
    let (code, stdout, _) = explain("builtin:spheres", "text");
    assert_eq!(code, Some(0));
    assert!(stdout.contains(
        "features ambient, directional_lights, lit, point_lights, shadows, shallow_depth\n"
    ));
    assert!(stdout.contains("  passes: 14 instead of 18\n    - transparent: condition \"blend\" is false\n    - points lines: condition \"points_lines\" is false\n    - composite transparent: condition \"blend\" is false\n    - composite points lines: condition \"points_lines\" is false\n"), "{stdout}");
    assert!(
        stdout.contains("  memory: 64.6 MiB physical instead of 64.8 MiB (256.0 KiB saved, 0%)\n"),
        "{stdout}"
    );
}

/// The shaders with feature-gated code, compiled for the scene's features only.
#[test]
fn a_scene_s_plan_lists_the_shader_variants_it_builds() {
    let (code, stdout, _) = explain("builtin:spheres", "text");
    assert_eq!(code, Some(0));
    let expected = "\nshader variants built:\n\
        \x20 gbuffer.wgsl {} instead of {textures, emissive_textures, metal_rough_textures, \
        normal_textures, occlusion_textures, double_sided, emissive, specular, clearcoat, \
        sheen}: gbuffer\n\
        \x20 light_tiled.wgsl {directional_lights, point_lights} instead of \
        {directional_lights, point_lights, spot_lights, environment, specular, clearcoat, \
        sheen}: debug shadows, debug cascades\n\
        \x20 light.wgsl {directional_lights, point_lights} instead of \
        {directional_lights, point_lights, spot_lights, environment, specular, clearcoat, \
        sheen}: light edges, light the rest\n";
    assert!(
        stdout.ends_with(expected),
        "no {expected:?} at the end of:\n{stdout}"
    );
    // builtin:unlit has no lights: the light passes and their variant are dropped.
    let (_, stdout, _) = explain("builtin:unlit", "text");
    let expected = "\nshader variants built:\n\
        \x20 gbuffer.wgsl {double_sided} instead of {textures, emissive_textures, \
        metal_rough_textures, normal_textures, occlusion_textures, double_sided, emissive, \
        specular, clearcoat, sheen}: gbuffer (unlit)\n";
    assert!(
        stdout.ends_with(expected),
        "no {expected:?} at the end of:\n{stdout}"
    );
}

#[test]
fn json_carries_the_features_and_the_dropped_passes() {
    let (code, stdout, _) = explain("builtin:unlit", "json");
    assert_eq!(code, Some(0));
    let plan: serde_json::Value = serde_json::from_str(&stdout).expect("explain emits JSON");
    assert_eq!(
        plan["features"],
        serde_json::json!(["no_lights", "shallow_depth", "unlit_only"])
    );
    let dropped: Vec<&str> = plan["culled"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|c| c["dropped"] == true)
        .map(|c| c["name"].as_str().unwrap())
        .collect();
    assert_eq!(
        dropped,
        [
            "gbuffer",
            "edges",
            "shadow maps",
            "light edges",
            "light the rest",
            "background",
            "transparent",
            "composite transparent",
            "points lines",
            "composite points lines",
            "auto exposure",
            "tonemap (auto exposure)",
            "debug normals",
            "debug lights",
            "debug shadows",
            "debug cascades"
        ]
    );
}

#[test]
fn a_shallow_scene_s_plan_says_which_depth_format_it_picks_and_why() {
    // On the WebGPU defaults depth32float-stencil8 falls back anyway: nothing is saved.
    let (code, stdout, stderr) = explain("builtin:spheres", "text");
    assert_eq!(code, Some(0), "{stderr}");
    for expected in [
        "depth format: a 24-bit unorm step is 1.8e-5 of the distance, within 6.1e-5: \
         shallow_depth, 24-bit unorm depth with standard Z\n",
        "  depth: depth24plus-stencil8 64x64 4x MSAA\n      format depth24plus-stencil8 \
         instead of depth32float-stencil8: condition \"shallow_depth\" holds\n",
    ] {
        assert!(stdout.contains(expected), "no {expected:?} in:\n{stdout}");
    }
    // lavapipe has depth32float-stencil8: the specialised plan saves half the depth, and
    // the material layers' targets a scene using every feature stores (16 bytes a sample:
    // lavapipe allows color_bytes_64).
    let (code, stdout, stderr) = explain_on("builtin:spheres", "text", "adapter");
    assert_eq!(code, Some(0), "{stderr}");
    for expected in [
        "    format of depth: depth24plus-stencil8 instead of depth32float-stencil8: \
         condition \"shallow_depth\" holds\n",
        "  memory: 64.6 MiB physical instead of 65.2 MiB (576.0 KiB saved, 1%)\n",
    ] {
        assert!(stdout.contains(expected), "no {expected:?} in:\n{stdout}");
    }
}

#[test]
fn a_scene_that_does_not_load_exits_1_naming_it() {
    let (code, _, stderr) = explain("builtin:nope", "text");
    assert_eq!(code, Some(1));
    assert!(
        stderr.contains("error: scene builtin:nope: unknown built-in scene `nope`"),
        "{stderr}"
    );
}
