//! The validation calls build scripts and CI use: whole directories of graph files and
//! shaders, every error of every file reported.

use rgraph_core::file::{validate_dir, validate_shader, ErrorKind, Registry};
use rgraph_core::CompileOptions;

/// The repository's own pipelines need the deferred plugins too; the root package's
/// build script and `tests/cli_validate.rs` check those.
#[test]
fn a_directory_of_valid_graphs_and_shaders_validates() {
    let validated = validate_dir(
        "tests/fixtures/valid/graphs",
        "tests/fixtures/valid/shaders",
        &Registry::with_builtins(),
        &CompileOptions::default(),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(validated.graphs.len(), 1, "{validated:?}");
    assert_eq!(validated.shaders.len(), 1, "{validated:?}");
}

#[test]
fn a_directory_of_bad_files_reports_every_file_s_errors() {
    let errors = validate_dir(
        "tests/fixtures",
        "tests/fixtures/shaders",
        &Registry::with_builtins(),
        &CompileOptions::default(),
    )
    .expect_err("the fixtures are bad");
    let text = errors.to_string();
    for file in [
        "malformed",
        "cycle",
        "zero_size",
        "sample_count",
        "binding_mismatch",
    ] {
        assert!(
            text.contains(&format!("tests/fixtures/{file}.ron:")),
            "{file}: {text}"
        );
    }
    assert!(
        text.contains("tests/fixtures/shaders/invalid.wgsl:4:12: error: no definition in scope")
    );
    assert_eq!(
        text.lines().count(),
        errors.0.len(),
        "one line per error:\n{text}"
    );
}

#[test]
fn an_invalid_shader_is_placed_where_naga_points() {
    let errors = validate_shader("tests/fixtures/shaders/invalid.wgsl").expect_err("invalid");
    assert!(matches!(errors.0[0].kind, ErrorKind::Shader { .. }));
    assert_eq!(
        errors.to_string(),
        "tests/fixtures/shaders/invalid.wgsl:4:12: error: no definition in scope for identifier: `colour`"
    );
}

#[test]
fn a_missing_directory_is_an_error() {
    let errors = validate_dir(
        "tests/no_such_dir",
        "tests/fixtures/shaders",
        &Registry::with_builtins(),
        &CompileOptions::default(),
    )
    .expect_err("missing");
    assert!(matches!(errors.0[0].kind, ErrorKind::Unreadable { .. }));
    assert!(errors
        .to_string()
        .starts_with("tests/no_such_dir:1:1: error: cannot read"));
}
