//! `rgraph validate` and `rgraph explain` as a user runs them: exit status, and
//! `FILE:LINE:COL: error:` lines naming the pass and resource for every kind of bad input.
//! No GPU is involved.

use std::process::{Command, Output};

fn rgraph(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rgraph"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("the rgraph binary runs")
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

/// Validates one fixture and returns its single error line, after checking exit 1, that
/// the program did not panic, and that the line starts with the file's position.
fn invalid(fixture: &str, line_col: &str) -> String {
    let path = format!("graph-core/tests/fixtures/{fixture}");
    let out = rgraph(&["validate", &path]);
    let (stdout, stderr) = (text(&out.stdout), text(&out.stderr));
    assert_eq!(
        out.status.code(),
        Some(1),
        "{fixture}: stdout {stdout} stderr {stderr}"
    );
    assert!(!stderr.contains("panicked"), "{fixture} panicked: {stderr}");
    let prefix = format!("{path}:{line_col}: error: ");
    let line = stdout
        .lines()
        .find(|l| l.starts_with(&prefix))
        .unwrap_or_else(|| panic!("{fixture}: no line starting {prefix:?} in:\n{stdout}"));
    line[prefix.len()..].to_owned()
}

#[test]
fn every_pipeline_and_shader_in_the_repository_is_valid() {
    let mut args = vec!["validate".to_owned()];
    for dir in ["pipelines", "shaders"] {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(dir);
        for entry in std::fs::read_dir(&dir).expect("directory exists") {
            let path = entry.expect("entry").path();
            if path.extension().is_some_and(|e| e == "ron" || e == "wgsl") {
                args.push(path.display().to_string());
            }
        }
    }
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let out = rgraph(&args);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stdout));
    assert!(text(&out.stderr).contains("file(s) valid for webgpu defaults"));
}

#[test]
fn malformed_ron_points_at_the_syntax_error() {
    assert_eq!(invalid("malformed.ron", "5:9"), "Expected comma");
}

#[test]
fn an_unknown_plugin_lists_the_known_ones() {
    let line = invalid("unknown_plugin.ron", "9:21");
    let expected = "pass \"sky\" uses plugin \"fullscren\", which is not registered (known: ";
    assert!(line.starts_with(expected), "{line}");
    assert!(
        line.contains(" fullscreen,") || line.contains(" fullscreen)"),
        "{line}"
    );
}

#[test]
fn a_parameter_of_the_wrong_type_names_the_pass_and_plugin() {
    assert_eq!(
        invalid("wrong_param_type.ron", "10:29"),
        "pass \"clear_depth\": parameters of plugin \"clear\": Expected float"
    );
}

#[test]
fn a_missing_shader_names_the_pass_and_the_path() {
    let line = invalid("missing_shader.ron", "10:21");
    assert!(
        line.starts_with(
            "pass \"sky\" (fullscreen): cannot read shader \
             \"graph-core/tests/fixtures/shaders/no_such_shader.wgsl\""
        ),
        "{line}"
    );
}

#[test]
fn an_invalid_shader_reports_the_shader_position_too() {
    assert_eq!(
        invalid("invalid_shader.ron", "10:21"),
        "pass \"sky\" (fullscreen): graph-core/tests/fixtures/shaders/invalid.wgsl:4:12: no \
         definition in scope for identifier: `colour`"
    );
}

#[test]
fn a_binding_mismatch_names_slot_resource_and_shader_type() {
    assert_eq!(
        invalid("binding_mismatch.ron", "20:34"),
        "pass \"average\" (fullscreen): shader \
         \"graph-core/tests/fixtures/shaders/sample_average.wgsl\" @group(0) @binding(0): slot \
         \"samples\" binds \"hdr\" (rgba16float, 1 sample), but the shader's `samples` is \
         texture_multisampled_2d<f32>"
    );
}

#[test]
fn a_cycle_names_its_passes_and_resources() {
    assert_eq!(
        invalid("cycle.ron", "8:16"),
        "cycle: passes \"a\", \"b\" must each run before the other (through \"y\", \"x\")"
    );
}

#[test]
fn a_zero_sized_texture_is_named() {
    assert_eq!(
        invalid("zero_size.ron", "4:9"),
        "texture \"tiny\" is zero-sized (0x16)"
    );
}

#[test]
fn an_unsupported_sample_count_lists_the_supported_ones() {
    assert_eq!(
        invalid("sample_count.ron", "4:9"),
        "texture \"msaa\": rgba8unorm does not support 8x multisampling on webgpu defaults \
         (supported: 1x, 4x)"
    );
}

#[test]
fn reading_what_no_pass_writes_names_reader_and_resource() {
    assert_eq!(
        invalid("read_before_write.ron", "11:30"),
        "pass \"light\" reads \"gbuffer.normal\", which no pass writes"
    );
}

#[test]
fn an_unreadable_file_is_an_io_error_with_exit_2() {
    let out = rgraph(&["validate", "no/such/graph.ron"]);
    assert_eq!(out.status.code(), Some(2));
    let stderr = text(&out.stderr);
    assert!(
        stderr.starts_with("error: no/such/graph.ron: cannot read the file: "),
        "{stderr}"
    );
}

#[test]
fn explain_prints_order_memory_and_culling_in_each_format() {
    let pipeline = "pipelines/postprocess_demo.ron";
    let out = rgraph(&["explain", "--pipeline", pipeline, "--size", "1280x720"]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let plan = text(&out.stdout);
    for expected in [
        "0. sky (render)",
        "1. tonemap (compute)",
        "2. present (render)",
        "memory: ",
    ] {
        assert!(
            plan.contains(expected),
            "{expected:?} missing from:\n{plan}"
        );
    }

    let out = rgraph(&["explain", "--pipeline", pipeline, "--format", "json"]);
    assert_eq!(out.status.code(), Some(0));
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).expect("explain emits JSON");
    assert_eq!(json["passes"].as_array().map(Vec::len), Some(3), "{json}");

    let out = rgraph(&["explain", "--pipeline", pipeline, "--format", "dot"]);
    assert_eq!(out.status.code(), Some(0));
    assert!(
        text(&out.stdout).starts_with("digraph"),
        "{}",
        text(&out.stdout)
    );
}

#[test]
fn explain_of_an_invalid_file_exits_1_with_positions() {
    let out = rgraph(&[
        "explain",
        "--pipeline",
        "graph-core/tests/fixtures/cycle.ron",
    ]);
    assert_eq!(out.status.code(), Some(1));
    let all = text(&out.stdout) + &text(&out.stderr);
    assert!(
        all.contains("graph-core/tests/fixtures/cycle.ron:8:16: error: cycle"),
        "{all}"
    );
}

#[test]
fn validate_checks_every_argument_and_exits_2_when_one_is_unusable() {
    let out = rgraph(&[
        "validate",
        "README.md",
        "no/such/graph.ron",
        "pipelines/postprocess_demo.ron",
    ]);
    assert_eq!(out.status.code(), Some(2));
    let stderr = text(&out.stderr);
    for expected in [
        "error: README.md: not a graph file (.ron) or shader (.wgsl)\n",
        "error: no/such/graph.ron: cannot read the file: ",
        "pipelines/postprocess_demo.ron: ok\n",
        "error: 2 of 3 file(s) could not be checked, 0 invalid\n",
    ] {
        assert!(stderr.contains(expected), "{expected:?} not in:\n{stderr}");
    }
    assert_eq!(text(&out.stdout), "");
}

#[test]
fn explain_exits_2_for_io_errors_and_writes_errors_only_to_stderr() {
    let out = rgraph(&[
        "explain",
        "--pipeline",
        "no/such/graph.ron",
        "--format",
        "dot",
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(text(&out.stdout), "", "errors must not reach `| dot`");
    assert!(
        text(&out.stderr).contains("no/such/graph.ron:1:1: error: cannot read the file: "),
        "{}",
        text(&out.stderr)
    );

    let out = rgraph(&[
        "explain",
        "--pipeline",
        "graph-core/tests/fixtures/cycle.ron",
        "--format",
        "dot",
    ]);
    assert_eq!(out.status.code(), Some(1));
    assert_eq!(text(&out.stdout), "");
    assert!(
        text(&out.stderr).contains("graph-core/tests/fixtures/cycle.ron:8:16: error: cycle"),
        "{}",
        text(&out.stderr)
    );

    let out = rgraph(&[
        "explain",
        "--pipeline",
        "pipelines/deferred_msaa_4x.ron",
        "--scene",
        "no/such/scene.glb",
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(text(&out.stdout), "");
    assert!(
        text(&out.stderr).contains("error: scene no/such/scene.glb: cannot read no/such/scene.glb"),
        "{}",
        text(&out.stderr)
    );
}

#[test]
fn explain_refuses_a_built_in_scene_parameter_beyond_its_limit_at_once() {
    let started = std::time::Instant::now();
    let out = rgraph(&[
        "explain",
        "--pipeline",
        "pipelines/deferred_msaa_4x.ron",
        "--scene",
        "builtin:lights?count=100000000",
    ]);
    assert_eq!(out.status.code(), Some(1));
    assert!(
        text(&out.stderr).contains(
            "error: scene builtin:lights?count=100000000: builtin:lights: `count=100000000`: a \
             whole number from 0 to 65536"
        ),
        "{}",
        text(&out.stderr)
    );
    // It once took 24 s and 12.5 GB: the limit is checked before anything is allocated.
    assert!(
        started.elapsed().as_secs() < 5,
        "took {:?}",
        started.elapsed()
    );
}

#[cfg(unix)]
#[test]
fn a_profile_that_is_a_device_is_refused_without_reading_it() {
    let out = rgraph(&[
        "validate",
        "pipelines/msaa_demo.ron",
        "--profile",
        "/dev/zero",
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        text(&out.stderr).contains(
            "--profile: \"/dev/zero\" is not webgpu, adapter or a readable profile file: not a \
             regular file (it is a character device)"
        ),
        "{}",
        text(&out.stderr)
    );
}
