//! Shader bindings declared in graph files are checked against the shader by naga
//! reflection when the file loads, without a GPU. Shaders are in `tests/fixtures/shaders/`.

use crate::ron_support;

use rgraph_core::file::{ErrorKind, PluginError};
use ron_support::{assert_error, compile_str, only_error};

const PATH: &str = "tests/fixtures/inline.ron";
const SHADER: &str = "tests/fixtures/shaders/bindings.wgsl";

/// A graph with one textured input "src" (rgba16float) and one full-screen pass `entry`
/// with `bindings`, writing "out".
fn fullscreen(entry: &str, bindings: &str) -> String {
    format!(
        r#"Graph(
resources: {{ "src": ImportedTexture(format: "rgba16float"), "out": Texture(format: "rgba8unorm") }},
passes: [
    (name: "draw", plugin: "fullscreen",
     params: (shader: "shaders/bindings.wgsl", entry: "{entry}", bindings: [{bindings}]),
     inputs: {{ "src": "src" }},
     outputs: {{ "color": "out" }}),
],
outputs: ["out"],
)"#
    )
}

fn binding_error(error: &ErrorKind) -> bool {
    matches!(
        error,
        ErrorKind::Plugin {
            error: PluginError::Binding { .. },
            ..
        }
    )
}

#[test]
fn a_matching_binding_compiles() {
    compile_str(&fullscreen(
        "sample_color",
        r#"Slot(binding: 0, slot: "src")"#,
    ))
    .unwrap_or_else(|e| panic!("{e}"));
}

#[test]
fn a_binding_the_shader_does_not_use_is_an_error() {
    let text = fullscreen(
        "sample_color",
        r#"Slot(binding: 0, slot: "src"), Sampler(binding: 7)"#,
    );
    let error = only_error(compile_str(&text));
    assert!(binding_error(&error.kind));
    assert_error(&error, PATH, 5, 14, &["draw", SHADER, "sample_color"]);
    assert!(error
        .to_string()
        .contains("@group(0) @binding(7): declared in the graph file"));
}

#[test]
fn a_binding_the_graph_file_does_not_declare_is_an_error() {
    let error = only_error(compile_str(&fullscreen("sample_color", "")));
    assert!(binding_error(&error.kind));
    assert_error(&error, PATH, 5, 14, &["draw", SHADER]);
    let text = error.to_string();
    assert!(
        text.contains("@group(0) @binding(0): the shader's `color` (texture_2d<f32>) is not bound")
    );
}

#[test]
fn a_float_texture_where_the_shader_wants_depth_is_an_error() {
    let text = fullscreen("sample_depth", r#"Slot(binding: 1, slot: "src")"#);
    let error = only_error(compile_str(&text));
    assert!(binding_error(&error.kind));
    assert_error(&error, PATH, 6, 23, &["draw", "src", SHADER]);
    assert!(error.to_string().contains(
        "slot \"src\" binds \"src\" (rgba16float, 1 sample), but the shader's `depth` is texture_depth_2d"
    ));
}

/// A graph declaring `features`, whose texture "depth" (`depth`, its declaration) is
/// cleared and then read by a full-screen pass as `texture_depth_2d`.
fn show_depth(features: &str, depth: &str) -> String {
    format!(
        r#"Graph(
features: [{features}],
resources: {{ "depth": {depth}, "out": Texture(format: "rgba8unorm") }},
passes: [
    (name: "clear", plugin: "clear", outputs: {{ "target": "depth" }}),
    (name: "show", plugin: "fullscreen",
     params: (shader: "shaders/bindings.wgsl", entry: "sample_depth",
              bindings: [Slot(binding: 1, slot: "depth")]),
     inputs: {{ "depth": "depth" }},
     outputs: {{ "color": "out" }}),
],
outputs: ["out"],
)"#
    )
}

#[test]
fn a_depth_texture_binds_as_texture_depth_2d() {
    compile_str(&show_depth("", r#"Texture(format: "depth32float")"#))
        .unwrap_or_else(|e| panic!("{e}"));
}

/// A texture whose format is a color one where a feature holds and a depth one otherwise
/// binds one way for all of them: a full-screen pass reading it as depth, which the
/// conditional color format cannot give, is an error naming the slot.
#[test]
fn a_texture_whose_conditional_format_binds_otherwise_is_an_error() {
    let text = show_depth(
        r#""compute""#,
        r#"Texture(format: "depth32float", format_if: [("compute", "r32float")])"#,
    );
    let error = only_error(compile_str(&text));
    assert!(binding_error(&error.kind), "{error}");
    assert!(
        error
            .to_string()
            .contains("slot \"depth\" binds \"depth\" (depth32float"),
        "{error}"
    );
}

/// A compute pass running `store` (a write-only rgba8unorm storage texture at binding 2)
/// with slot "dst" declared as `slots`.
fn store(resources: &str, slots: &str) -> String {
    format!(
        r#"Graph(
resources: {{ {resources} }},
passes: [
    (name: "fill", plugin: "compute",
     params: (shader: "shaders/bindings.wgsl", entry: "store", dispatch: PerTexel("dst"),
              bindings: [Slot(binding: 2, slot: "dst")]),
     {slots}),
],
outputs: ["done"],
)"#
    )
}

#[test]
fn a_storage_texture_compiles_when_written_through_an_output_slot() {
    let text = store(
        r#""out": Texture(format: "rgba8unorm")"#,
        r#"outputs: { "dst": "out" }"#,
    );
    compile_str(&text.replace(r#"["done"]"#, r#"["out"]"#)).unwrap_or_else(|e| panic!("{e}"));
}

#[test]
fn a_storage_binding_through_an_input_only_slot_is_an_error() {
    let text = store(
        r#""out": ImportedTexture(format: "rgba8unorm")"#,
        r#"inputs: { "dst": "out" }"#,
    );
    let error = only_error(compile_str(&text.replace(r#"["done"]"#, r#"["out"]"#)));
    assert!(binding_error(&error.kind));
    assert_error(&error, PATH, 7, 23, &["fill", "dst", "out", SHADER]);
    assert!(
        error.to_string().contains("so the slot belongs in outputs"),
        "{error}"
    );
}

#[test]
fn a_storage_texture_of_another_format_is_an_error() {
    let text = store(
        r#""out": Texture(format: "rgba16float")"#,
        r#"outputs: { "dst": "done" }"#,
    );
    let error = only_error(compile_str(&text.replace(r#""out""#, r#""done""#)));
    assert!(binding_error(&error.kind));
    assert_error(&error, PATH, 7, 24, &["fill", "dst", "done", SHADER]);
    assert!(error
        .to_string()
        .contains("but the shader's `stored` is texture_storage_2d<rgba8unorm, write>"));
}

#[test]
fn uniform_values_must_fill_the_uniform_exactly() {
    let text = fullscreen("tinted", "Uniform(binding: 3, values: [1.0, 0.5, 0.25])")
        .replace(r#"inputs: { "src": "src" },"#, "");
    let error = only_error(compile_str(&text));
    assert!(binding_error(&error.kind));
    assert_error(&error, PATH, 5, 14, &["draw", SHADER]);
    assert!(error.to_string().contains(
        "3 values (12 bytes) are given, but the shader's `tint` is var<uniform> of 16 bytes"
    ));
}

#[test]
fn every_color_attachment_needs_a_fragment_output() {
    let text = fullscreen(
        "tinted",
        "Uniform(binding: 3, values: [1.0, 0.5, 0.25, 1.0])",
    )
    .replace(r#"inputs: { "src": "src" },"#, "")
    .replace(
        r#"outputs: { "color": "out" }"#,
        r#"outputs: { "color": "out", "extra": "src" }"#,
    );
    let error = only_error(compile_str(&text));
    assert_error(&error, PATH, 7, 42, &["draw", "extra", "src", "tinted"]);
    assert!(
        error.to_string().contains("is color attachment 1"),
        "{error}"
    );
}

#[test]
fn fragment_inputs_must_come_from_the_full_screen_vertex_stage() {
    let text = fullscreen("needs_normal", "").replace(r#"inputs: { "src": "src" },"#, "");
    let error = only_error(compile_str(&text));
    assert_error(&error, PATH, 5, 14, &["draw", "needs_normal"]);
    assert!(
        error.to_string().contains("fragment input @location(1)"),
        "{error}"
    );
}

#[test]
fn a_missing_entry_point_lists_the_shader_s_entry_points() {
    let text = fullscreen("fs_mian", r#"Slot(binding: 0, slot: "src")"#);
    let error = only_error(compile_str(&text));
    assert_error(&error, PATH, 5, 14, &["draw", SHADER, "fs_mian"]);
    assert!(error
        .to_string()
        .contains("(it has: sample_color, sample_depth, tinted, needs_normal)"));
}

#[test]
fn a_dispatch_following_an_unbound_slot_is_an_error() {
    let text = store(
        r#""out": Texture(format: "rgba8unorm")"#,
        r#"outputs: { "dst": "out" }"#,
    )
    .replace(r#"PerTexel("dst")"#, r#"PerTexel("nope")"#)
    .replace(r#"["done"]"#, r#"["out"]"#);
    let error = only_error(compile_str(&text));
    assert_error(&error, PATH, 5, 14, &["fill", "nope"]);
}

#[test]
fn uniform_values_must_be_finite() {
    for (value, shown) in [("NaN", "NaN"), ("inf", "inf"), ("-inf", "-inf")] {
        let values = format!("Uniform(binding: 3, values: [1.0, {value}, 0.25, 1.0])");
        let text = fullscreen("tinted", &values).replace(r#"inputs: { "src": "src" },"#, "");
        let error = only_error(compile_str(&text));
        assert_error(&error, PATH, 5, 14, &["draw", SHADER]);
        assert!(
            error.to_string().contains(&format!(
                "uniform value #1 is {shown}; values must be finite"
            )),
            "{error}"
        );
    }
}

#[test]
fn fixed_dispatch_counts_must_be_from_1_to_65535() {
    let fill = |dispatch: &str| {
        store(
            r#""out": Texture(format: "rgba8unorm")"#,
            r#"outputs: { "dst": "out" }"#,
        )
        .replace(r#"["done"]"#, r#"["out"]"#)
        .replace(r#"PerTexel("dst")"#, dispatch)
    };
    compile_str(&fill("Workgroups(65535, 1, 1)")).unwrap_or_else(|e| panic!("{e}"));
    for (dispatch, count, axis) in [
        ("Workgroups(65536, 1, 1)", 65536, "x"),
        ("Workgroups(0, 0, 0)", 0, "x"),
        ("Workgroups(4, 4, 0)", 0, "z"),
    ] {
        let error = only_error(compile_str(&fill(dispatch)));
        assert!(
            error.to_string().ends_with(&format!(
                "dispatch {dispatch} has {count} in {axis}: each count must be from 1 to 65535"
            )),
            "{error}"
        );
        assert!(error.to_string().contains("\"fill\""), "{error}");
    }
}

#[test]
fn clear_colors_must_be_finite_and_depths_within_0_and_1() {
    let clear = |params: &str, format: &str| {
        format!(
            r#"Graph(
resources: {{ "t": Texture(format: "{format}") }},
passes: [(name: "wipe", plugin: "clear", params: ({params}), outputs: {{ "target": "t" }})],
outputs: ["t"],
)"#
        )
    };
    for (params, format, expected) in [
        (
            "color: (NaN, 0.0, 0.0, 1.0)",
            "rgba8unorm",
            "clear color [NaN, 0.0, 0.0, 1.0] is not finite",
        ),
        (
            "color: (0.0, inf, 0.0, 1.0)",
            "rgba8unorm",
            "clear color [0.0, inf, 0.0, 1.0] is not finite",
        ),
        (
            "depth: 2.0",
            "depth32float",
            "clear depth 2 is not within 0.0 ..= 1.0",
        ),
        (
            "depth: NaN",
            "depth32float",
            "clear depth NaN is not within 0.0 ..= 1.0",
        ),
    ] {
        let error = only_error(compile_str(&clear(params, format)));
        assert!(error.to_string().ends_with(expected), "{error}");
        assert!(error.to_string().contains("\"wipe\""), "{error}");
    }
}
