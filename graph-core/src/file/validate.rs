//! Validation without a GPU, for build scripts, CI and `rgraph validate`: graph files are
//! loaded and compiled, WGSL files are parsed and validated by naga.

use std::path::{Path, PathBuf};

use super::error::{ErrorKind, FileError, FileErrors, Location};
use super::load::load_file_in;
use super::params::GraphParams;
use super::registry::Registry;
use crate::compile::CompileOptions;
use crate::folders::Folders;
use crate::plan::Plan;
use crate::position::Position;
use crate::shader::{Shader, ShaderError};

/// What [`validate_dir`] checked, sorted: graph files and shaders.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Validated {
    /// The graph files checked (`.ron`).
    pub graphs: Vec<PathBuf>,
    /// The WGSL files checked (`.wgsl`).
    pub shaders: Vec<PathBuf>,
}

/// Loads and checks one graph file for `options` (its device profile and output size),
/// as [`LoadedGraph::validate`](super::LoadedGraph::validate) does, returning the plan for no features.
pub fn validate_file(
    path: impl AsRef<Path>,
    registry: &Registry,
    options: &CompileOptions,
) -> Result<Plan, FileErrors> {
    validate_file_in(path.as_ref(), registry, options, &Folders::new())
}

/// [`validate_file`], the file's references also allowed into `extra` folders.
fn validate_file_in(
    path: &Path,
    registry: &Registry,
    options: &CompileOptions,
    extra: &Folders,
) -> Result<Plan, FileErrors> {
    load_file_in(path, registry, &GraphParams::new(), extra)?.validate(options)
}

/// Parses and validates one WGSL file with naga.
pub fn validate_shader(path: impl AsRef<Path>) -> Result<(), FileErrors> {
    Shader::load(path)
        .map(drop)
        .map_err(|e| FileErrors(vec![shader_error(e)]))
}

/// Validates every `.ron` file under `pipelines` as a graph and every `.wgsl` file under
/// `shaders` (both searched recursively), reporting every error of every file. The graph
/// files may name files in both folders (and those `registry` allows).
pub fn validate_dir(
    pipelines: impl AsRef<Path>,
    shaders: impl AsRef<Path>,
    registry: &Registry,
    options: &CompileOptions,
) -> Result<Validated, FileErrors> {
    let mut errors = Vec::new();
    let validated = Validated {
        graphs: files(pipelines.as_ref(), "ron", &mut errors),
        shaders: files(shaders.as_ref(), "wgsl", &mut errors),
    };
    for shader in &validated.shaders {
        errors.extend(validate_shader(shader).err().into_iter().flat_map(|e| e.0));
    }
    let mut folders = Folders::new();
    for dir in [pipelines.as_ref(), shaders.as_ref()] {
        folders.allow_virtual(dir);
    }
    for graph in &validated.graphs {
        errors.extend(
            validate_file_in(graph, registry, options, &folders)
                .err()
                .into_iter()
                .flat_map(|e| e.0),
        );
    }
    if errors.is_empty() {
        Ok(validated)
    } else {
        Err(FileErrors(errors))
    }
}

/// A shader error as a file error, placed where naga points.
fn shader_error(error: ShaderError) -> FileError {
    match error {
        ShaderError::Unreadable { path, reason } => FileError {
            location: Location {
                path,
                at: Position::START,
            },
            kind: ErrorKind::Unreadable { reason },
        },
        ShaderError::Invalid {
            path, at, message, ..
        } => FileError {
            location: Location { path, at },
            kind: ErrorKind::Shader { message },
        },
    }
}

/// Files under `dir` whose extension is `extension`, sorted.
fn files(dir: &Path, extension: &str, errors: &mut Vec<FileError>) -> Vec<PathBuf> {
    let mut found = Vec::new();
    let mut pending = vec![dir.to_path_buf()];
    while let Some(dir) = pending.pop() {
        let entries = match std::fs::read_dir(&dir) {
            Ok(entries) => entries,
            Err(e) => {
                errors.push(FileError {
                    location: Location {
                        path: dir.display().to_string(),
                        at: Position::START,
                    },
                    kind: ErrorKind::Unreadable {
                        reason: e.to_string(),
                    },
                });
                continue;
            }
        };
        for path in entries.filter_map(|e| e.ok()).map(|e| e.path()) {
            if path.is_dir() {
                pending.push(path);
            } else if path.extension().is_some_and(|e| e == extension) {
                found.push(path);
            }
        }
    }
    found.sort();
    found
}
