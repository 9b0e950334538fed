//! Bad graph files: each is a clear error at the right line and column that names the
//! pass and the resource, never a panic. Fixtures are in `tests/fixtures/`.

use crate::ron_support;

use rgraph_core::file::ErrorKind;
use rgraph_core::GraphError;
use ron_support::{assert_error, compile_file, only_error};

fn fixture(name: &str) -> String {
    format!("tests/fixtures/{name}.ron")
}

#[test]
fn malformed_ron_points_at_the_token_after_the_missing_comma() {
    let path = fixture("malformed");
    let error = only_error(compile_file(&path));
    assert!(matches!(error.kind, ErrorKind::Syntax { .. }));
    assert_error(&error, &path, 5, 9, &[]);
    assert!(error.to_string().ends_with("Expected comma"), "{error}");
}

#[test]
fn an_unknown_plugin_is_named_with_the_registered_ones() {
    let path = fixture("unknown_plugin");
    let error = only_error(compile_file(&path));
    assert_error(&error, &path, 9, 21, &["sky", "fullscren"]);
    assert!(error
        .to_string()
        .contains("known: blit, clear, compute, copy, fullscreen"));
}

#[test]
fn a_parameter_of_the_wrong_type_points_into_the_parameters() {
    let path = fixture("wrong_param_type");
    let error = only_error(compile_file(&path));
    assert!(matches!(error.kind, ErrorKind::Params { .. }));
    assert_error(&error, &path, 10, 29, &["clear_depth", "clear"]);
    assert!(error.to_string().ends_with("Expected float"), "{error}");
}

#[test]
fn a_missing_shader_names_its_path_and_the_pass() {
    let path = fixture("missing_shader");
    let error = only_error(compile_file(&path));
    assert_error(
        &error,
        &path,
        10,
        21,
        &["sky", "tests/fixtures/shaders/no_such_shader.wgsl"],
    );
    assert!(error.to_string().contains("cannot read shader"));
}

#[test]
fn an_invalid_shader_carries_naga_s_position_in_the_shader() {
    let path = fixture("invalid_shader");
    let error = only_error(compile_file(&path));
    assert_error(&error, &path, 10, 21, &["sky"]);
    assert!(
        error
            .to_string()
            .contains("tests/fixtures/shaders/invalid.wgsl:4:12: no definition in scope"),
        "{error}"
    );
}

#[test]
fn a_binding_mismatch_names_slot_resource_shader_and_binding() {
    let path = fixture("binding_mismatch");
    let error = only_error(compile_file(&path));
    assert_error(
        &error,
        &path,
        20,
        34,
        &[
            "average",
            "samples",
            "hdr",
            "tests/fixtures/shaders/sample_average.wgsl",
        ],
    );
    let text = error.to_string();
    assert!(text.contains("@group(0) @binding(0)"), "{text}");
    assert!(text.contains("(rgba16float, 1 sample)"), "{text}");
    assert!(text.contains("texture_multisampled_2d<f32>"), "{text}");
}

#[test]
fn a_cycle_lists_its_passes_and_resources_at_the_first_pass() {
    let path = fixture("cycle");
    let error = only_error(compile_file(&path));
    assert!(matches!(
        error.kind,
        ErrorKind::Graph(GraphError::Cycle { .. })
    ));
    assert_error(&error, &path, 8, 16, &["a", "b", "x", "y"]);
}

#[test]
fn a_zero_sized_texture_points_at_its_declaration() {
    let path = fixture("zero_size");
    let error = only_error(compile_file(&path));
    assert!(matches!(
        error.kind,
        ErrorKind::Graph(GraphError::ZeroSize { .. })
    ));
    assert_error(&error, &path, 4, 9, &["tiny"]);
}

#[test]
fn an_unsupported_sample_count_points_at_the_declaration() {
    let path = fixture("sample_count");
    let error = only_error(compile_file(&path));
    assert!(matches!(
        error.kind,
        ErrorKind::Graph(GraphError::UnsupportedSampleCount { .. })
    ));
    assert_error(&error, &path, 4, 9, &["msaa"]);
    assert!(error.to_string().contains("8x"), "{error}");
}

#[test]
fn reading_what_no_pass_writes_points_at_the_input() {
    let path = fixture("read_before_write");
    let error = only_error(compile_file(&path));
    assert_eq!(
        error.to_string(),
        format!(
            "{path}:11:30: error: pass \"light\" reads \"gbuffer.normal\", which no pass writes"
        )
    );
}

#[test]
fn an_unreadable_file_is_an_error_not_a_panic() {
    let path = fixture("no_such_file");
    let error = only_error(compile_file(&path));
    assert!(matches!(error.kind, ErrorKind::Unreadable { .. }));
    assert_error(&error, &path, 1, 1, &[]);
}

/// A valid graph: one clear of one exported texture.
const CLEAR: &str = r#"Graph(
    resources: { "c": Texture(format: "rgba8unorm") },
    passes: [(name: "fill", plugin: "clear", params: (color: (0.0, 0.0, 0.0, 1.0)), outputs: { "target": "c" })],
    outputs: ["c"],
)"#;

#[test]
fn a_utf8_byte_order_mark_is_skipped_and_not_counted() {
    ron_support::compile_str(&format!("\u{feff}{CLEAR}")).unwrap_or_else(|e| panic!("{e}"));
    let error = only_error(ron_support::compile_str(&format!(
        "\u{feff}{}",
        CLEAR.replace("passes:", "passes")
    )));
    assert_eq!(error.location.at.line, 3, "{error}");
    assert_eq!(error.location.at.column, 12, "{error}");
}

#[test]
fn parser_messages_do_not_leak_ron_s_api() {
    let deep = format!("{}{}", "[".repeat(200), "]".repeat(200));
    let nested = CLEAR.replace("params: (color:", &format!("params: (x: {deep}, color:"));
    for (text, expected) in [
        (nested, "values are nested more than 128 levels deep"),
        (
            CLEAR.replace("plugin:", "3: 1, plugin:"),
            "`3` is not a valid field or variant name",
        ),
    ] {
        let message = only_error(ron_support::compile_str(&text)).to_string();
        assert!(message.ends_with(expected), "{message}");
        for internal in ["ron::", "serde_stacker", "r#"] {
            assert!(!message.contains(internal), "{message}");
        }
    }
}

#[test]
fn a_shader_s_byte_order_mark_is_skipped() {
    let source = "\u{feff}@compute @workgroup_size(1) fn main() {}";
    rgraph_core::shader::Shader::parse("bom.wgsl", source).unwrap_or_else(|e| panic!("{e}"));
}

#[cfg(unix)]
#[test]
fn a_shader_path_to_a_device_or_fifo_is_refused_without_reading() {
    // In the graph file's folder: a FIFO, and a link to a device, which leads out of it.
    let dir = tempfile::tempdir().unwrap();
    let fifo = dir.path().join("pipe.wgsl");
    let made = std::process::Command::new("mkfifo").arg(&fifo).status();
    assert!(made.is_ok_and(|s| s.success()), "mkfifo failed");
    std::os::unix::fs::symlink("/dev/zero", dir.path().join("zero.wgsl")).unwrap();
    let graph = dir.path().join("g.ron");
    for (shader, ending) in [
        ("pipe.wgsl", "not a regular file (it is a FIFO)".to_owned()),
        (
            "zero.wgsl",
            format!(
                "leads (through a symbolic link) to /dev/zero, outside the folders graph files \
                 may read ({}); another is allowed with --graph-root DIR",
                dir.path().display()
            ),
        ),
        (
            "/dev/zero",
            "is an absolute path; a graph file names files relative to its own folder".to_owned(),
        ),
    ] {
        let text = format!(
            r#"Graph(
    resources: {{ "c": Texture(format: "rgba8unorm") }},
    passes: [(name: "sky", plugin: "fullscreen", params: (shader: "{shader}"), outputs: {{ "color": "c" }})],
    outputs: ["c"],
)"#
        );
        let registry = rgraph_core::file::Registry::with_builtins();
        let errors = rgraph_core::file::load_str(&graph, &text, &registry)
            .map(drop)
            .expect_err("the shader is refused");
        let error = only_error(Err(errors));
        assert!(error.to_string().ends_with(&ending), "{error}");
        assert!(error.to_string().contains("\"sky\""), "{error}");
    }
}
