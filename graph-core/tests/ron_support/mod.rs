//! Helpers shared by the graph-file tests: loading and compiling files against the
//! built-in plugins and checking where each error points and what it names.

use std::path::Path;

use rgraph_core::file::{load_file, load_str, ErrorKind, FileError, FileErrors, Registry};
use rgraph_core::{CompileOptions, Plan};

/// The built-in plugins, with the workspace's folders open to graph files (the fixtures
/// name the shipped shaders/ from tests/fixtures/).
pub fn registry() -> Registry {
    let mut registry = Registry::with_builtins();
    registry
        .allow_graph_root(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
        .expect("the workspace is a folder");
    registry
}

/// Loads and compiles `path` for the WebGPU defaults at 1080p.
pub fn compile_file(path: &str) -> Result<Plan, FileErrors> {
    load_file(path, &registry())?.compile(&CompileOptions::default())
}

/// Loads and compiles `text` as if read from `tests/fixtures/inline.ron`.
pub fn compile_str(text: &str) -> Result<Plan, FileErrors> {
    load_str("tests/fixtures/inline.ron", text, &registry())?.compile(&CompileOptions::default())
}

/// The one error `result` is expected to hold.
pub fn only_error(result: Result<Plan, FileErrors>) -> FileError {
    match result {
        Ok(_) => panic!("expected the graph to be rejected"),
        Err(errors) if errors.0.len() == 1 => errors.0.into_iter().next().unwrap(),
        Err(errors) => panic!("expected exactly one error, got:\n{errors}"),
    }
}

/// Asserts the error's rendering: `path:line:col: error: ` and then a message containing
/// every one of `names` (quoted, as messages quote names).
pub fn assert_error(error: &FileError, path: &str, line: usize, column: usize, names: &[&str]) {
    let text = error.to_string();
    let prefix = format!("{path}:{line}:{column}: error: ");
    assert!(
        text.starts_with(&prefix),
        "expected {prefix:?}..., got {text:?}"
    );
    for name in names {
        assert!(
            text.contains(&format!("\"{name}\"")),
            "{text:?} does not name \"{name}\""
        );
    }
}

/// A temporary folder holding `files` (`(path, text)`, paths relative to it; their
/// folders are made).
pub fn folder(files: &[(&str, &str)]) -> tempfile::TempDir {
    let dir = tempfile::tempdir().expect("a temporary folder");
    for (name, text) in files {
        let path = dir.path().join(name);
        std::fs::create_dir_all(path.parent().unwrap()).expect("a writable folder");
        std::fs::write(path, text).expect("a writable folder");
    }
    dir
}

/// The errors loading `path` against the built-in plugins gives, each as `FILE:LINE:COL`
/// and its kind; the file must not load.
pub fn located_errors(path: &Path) -> Vec<(String, ErrorKind)> {
    match load_file(path, &Registry::with_builtins()) {
        Ok(_) => panic!("{} loaded", path.display()),
        Err(errors) => errors
            .0
            .into_iter()
            .map(|e| (format!("{}:{}", e.location.path, e.location.at), e.kind))
            .collect(),
    }
}
