//! Loading a graph file: parse, look up plugins and their parameters, read conditions,
//! resolve names, order passes, declare. Every error found before declaring is reported together.

use std::path::{Path, PathBuf};

use typed_arena::Arena;

use super::compose::Composer;
use super::declare::declare;
use super::error::{ErrorKind, FileError, FileErrors, Location};
use super::loaded::LoadedGraph;
use super::param_uses;
use super::params::GraphParams;
use super::plugin::Prepared;
use super::references::{ReferenceError, References};
use super::registry::Registry;
use super::schema::{self, FileKind, GraphFile, Name, PresetFile};
use super::shown::Shown;
use super::source::Source;
use super::{conditions, names, order, ron_message};
use crate::bounded_read::{self, ReadError};
use crate::embedded;
use crate::folders::Folders;
use crate::position::Position;

/// Reads and declares the graph file at `path` (a regular file of at most
/// [`bounded_read::MAX_GRAPH_FILE_BYTES`]; a built-in file when a relative `path` is not on
/// disk, see [`embedded`]), every parameter at its default. Shader paths in it resolve
/// against the file's directory, and must stay inside the folders [`Registry`] allows;
/// messages show `path` as given. Compile the result with [`LoadedGraph::compile`].
pub fn load_file(path: impl AsRef<Path>, registry: &Registry) -> Result<LoadedGraph, FileErrors> {
    load_file_with(path, registry, &GraphParams::new())
}

/// [`load_file`] with values for the file's parameters (see [`GraphParams`]). A value for a
/// parameter the file does not declare, or a value a texture cannot take, is an error.
pub fn load_file_with(
    path: impl AsRef<Path>,
    registry: &Registry,
    params: &GraphParams,
) -> Result<LoadedGraph, FileErrors> {
    load_file_in(path.as_ref(), registry, params, &Folders::new())
}

/// [`load_file_with`], the file's references also allowed into `extra` folders.
pub(super) fn load_file_in(
    path: &Path,
    registry: &Registry,
    params: &GraphParams,
    extra: &Folders,
) -> Result<LoadedGraph, FileErrors> {
    let references = References::of_file(path, registry.roots(), extra);
    load_text(path, &read(path)?, registry, params, &references)
}

/// Declares the graph file whose text is `text`, as if read from `path`, every parameter
/// at its default.
pub fn load_str(
    path: impl AsRef<Path>,
    text: &str,
    registry: &Registry,
) -> Result<LoadedGraph, FileErrors> {
    load_str_with(path, text, registry, &GraphParams::new())
}

/// [`load_str`] with values for the file's parameters, as [`load_file_with`]. A preset
/// (`Preset(base: "FILE.ron", passes: {..})`) is its base file, read from the preset's
/// folder, with the passes it names changed; errors name the file each part is written in.
pub fn load_str_with(
    path: impl AsRef<Path>,
    text: &str,
    registry: &Registry,
    params: &GraphParams,
) -> Result<LoadedGraph, FileErrors> {
    let path = path.as_ref();
    let references = References::of_file(path, registry.roots(), &Folders::new());
    load_text(path, text, registry, params, &references)
}

/// [`load_str_with`], the graph's references resolved by `references`.
fn load_text(
    path: &Path,
    text: &str,
    registry: &Registry,
    params: &GraphParams,
    references: &References,
) -> Result<LoadedGraph, FileErrors> {
    let arena = Arena::new();
    let (source, read) = read_graph(path, without_bom(text), &arena, references)?;
    let values = read.values.overridden_by(params);
    load_graph(
        &source,
        read.file,
        read.errors,
        registry,
        &values,
        references,
    )
}

/// A graph file read, its parts written out: with a preset's values for its base's
/// parameters and the errors in its uses' bindings.
struct Read<'a> {
    file: GraphFile<'a>,
    values: GraphParams,
    errors: Vec<FileError>,
}

/// The graph the file at `path` holds, its parts written out (see [`compose`]), and the
/// source that places its names. A graph file is read as written; a part as the graph that
/// checks it alone; a preset as its base with its changes.
fn read_graph<'a>(
    path: &'a Path,
    text: &'a str,
    arena: &'a Arena<(PathBuf, String)>,
    references: &References,
) -> Result<(Source<'a>, Read<'a>), FileErrors> {
    let mut source = Source::new(path, text);
    let syntax = |source: &Source<'_>, e| FileErrors(vec![source.syntax(&e)]);
    let (file, composer, values) = match schema::kind(text) {
        FileKind::Graph => {
            let graph = schema::parse(text).map_err(|e| syntax(&source, e))?;
            let mut composer = Composer::new(arena, references, &graph.features);
            (
                composer.graph(&mut source, graph),
                composer,
                GraphParams::new(),
            )
        }
        FileKind::Part => {
            let part = schema::parse_part(text).map_err(|e| syntax(&source, e))?;
            let mut composer = Composer::new(arena, references, &part.features);
            let file = composer.part_alone(&mut source, path, part);
            (file, composer, GraphParams::new())
        }
        FileKind::Preset => {
            let preset = schema::parse_preset(text).map_err(|e| syntax(&source, e))?;
            let (base_path, base_text) = read_base(&source, &preset, references)?;
            let (base_path, base_text) = arena.alloc((base_path, base_text));
            let base_text = without_bom(base_text);
            source = Source::with_base(path, text, (base_path, base_text));
            let mut graph = schema::parse(base_text)
                .map_err(|e| syntax(&Source::new(base_path, base_text), e))?;
            let values = preset_values(&preset);
            for feature in &preset.features {
                if !graph
                    .features
                    .iter()
                    .any(|f| f.as_str() == feature.as_str())
                {
                    graph.features.push(feature.clone());
                }
            }
            let mut composer = Composer::new(arena, references, &graph.features);
            let mut file = composer.graph(&mut source, graph);
            apply_preset(&mut source, &mut composer, preset, base_path, &mut file);
            (file, composer, values)
        }
    };
    let errors = composer.finish(&source, &file)?;
    Ok((
        source,
        Read {
            file,
            values,
            errors,
        },
    ))
}

/// The values a preset gives its base's parameters.
fn preset_values(preset: &PresetFile<'_>) -> GraphParams {
    preset
        .values
        .0
        .iter()
        .fold(GraphParams::new(), |values, (name, value)| {
            values.with(name.as_str(), *value)
        })
}

/// Declares a parsed graph file: look up plugins and their parameters, read conditions,
/// resolve names, order passes, declare.
/// `bindings` are the errors in the uses' bindings, reported with what declaring finds
/// (a plugin refusing the resource bound is the same mistake, seen from the pass).
fn load_graph(
    source: &Source<'_>,
    file: GraphFile<'_>,
    bindings: Vec<FileError>,
    registry: &Registry,
    params: &GraphParams,
    references: &References,
) -> Result<LoadedGraph, FileErrors> {
    let mut errors = Vec::new();
    let values = param_uses::resolve(source, &file, params, &mut errors);
    let prepared = prepare(source, &file, registry, &values, &mut errors);
    let conditions = conditions::read(source, &file, &mut errors);
    let edges = names::resolve(source, &file, &conditions, &mut errors);
    let order = order::sort(source, &file, &edges, &mut errors);
    if !errors.is_empty() {
        return Err(FileErrors::sorted(
            errors.into_iter().chain(bindings).collect(),
        ));
    }
    let declared = declare(
        source, &file, prepared, conditions, &order, values, references,
    );
    match (declared, bindings.is_empty()) {
        (Ok(loaded), true) => Ok(loaded),
        (Ok(_), false) => Err(FileErrors::sorted(bindings)),
        (Err(e), _) => Err(FileErrors::sorted(
            e.0.into_iter().chain(bindings).collect(),
        )),
    }
}

/// The path and text of a preset's base (relative to the preset's folder, inside the
/// folders `references` allows), which must be a graph file, not another preset.
fn read_base(
    main: &Source<'_>,
    preset: &PresetFile<'_>,
    references: &References,
) -> Result<(PathBuf, String), FileErrors> {
    let error = |kind| FileErrors(vec![main.error(&preset.base, kind)]);
    let reference = preset.base.as_str();
    let max = bounded_read::MAX_GRAPH_FILE_BYTES;
    let named = references
        .read(main.dir(), reference, max)
        .map_err(|e| match e {
            ReferenceError::Refused(reason) => error(ErrorKind::Reference {
                what: "the preset's base",
                reference: Shown(reference).to_string(),
                reason,
            }),
            ReferenceError::Unreadable {
                path,
                reason: ReadError::NotUtf8(e),
            } => FileErrors(vec![not_utf8(&path, &e)]),
            ReferenceError::Unreadable { path, reason } => error(ErrorKind::PresetBase {
                base: path.display().to_string(),
                reason: reason.to_string(),
            }),
        })?;
    if schema::kind(without_bom(&named.text)) == FileKind::Preset {
        return Err(error(ErrorKind::PresetOfPreset {
            base: named.path.display().to_string(),
        }));
    }
    Ok((named.path, named.text))
}

/// Applies `preset` to its base's graph `file`: the passes it names changed, the names it
/// rebinds renamed, those it removes left out, its passes and part uses added after the passes it names, its
/// resources added and its outputs in place of the base's. Errors go to `composer`'s.
fn apply_preset<'a>(
    source: &mut Source<'a>,
    composer: &mut Composer<'a, '_>,
    preset: PresetFile<'a>,
    base: &Path,
    file: &mut GraphFile<'a>,
) {
    let mut errors = Vec::new();
    for (name, change) in preset.passes.0 {
        let Some(p) = find_pass(source, file, &name, base, &mut errors) else {
            continue;
        };
        let pass = &mut file.passes[p];
        if let Some(params) = change.params {
            pass.params = Some(params);
        }
        if let Some(inputs) = change.inputs {
            pass.inputs = inputs;
        }
        if let Some(outputs) = change.outputs {
            pass.outputs = outputs;
        }
        if let Some(optional) = change.optional {
            pass.optional = optional;
        }
    }
    for (from, to) in &preset.rebind.0 {
        if !rename(file, from.as_str(), to) {
            errors.push(source.error(
                from,
                ErrorKind::UnknownRebind {
                    name: from.as_str().to_owned(),
                    base: base.display().to_string(),
                },
            ));
        }
    }
    for name in &preset.remove {
        if let Some(p) = find_pass(source, file, name, base, &mut errors) {
            file.passes.remove(p);
        }
    }
    for (name, entries) in preset.after.0 {
        let Some(p) = find_pass(source, file, &name, base, &mut errors) else {
            continue;
        };
        let added = composer.added(source, entries);
        file.resources.0.extend(added.resources.0);
        file.passes.splice(p + 1..p + 1, added.passes);
    }
    file.resources.0.extend(preset.resources.0);
    if let Some(outputs) = preset.outputs {
        file.outputs = outputs;
    }
    composer.errors.extend(errors);
}

/// Renames `from` to `to` in `file`'s resources and passes' slots (not its outputs);
/// whether `file` had it.
fn rename<'a>(file: &mut GraphFile<'a>, from: &str, to: &Name<'a>) -> bool {
    let resources = file.resources.0.iter_mut().map(|(name, _)| name);
    let slots = file
        .passes
        .iter_mut()
        .flat_map(|pass| pass.inputs.0.iter_mut().chain(pass.outputs.0.iter_mut()))
        .map(|(_, name)| name);
    let mut found = false;
    for name in resources.chain(slots).filter(|name| name.as_str() == from) {
        *name = to.clone();
        found = true;
    }
    found
}

/// The index of the pass a preset names in its base's graph `file`, or the error saying
/// which passes there are.
fn find_pass(
    source: &Source<'_>,
    file: &GraphFile<'_>,
    name: &Name<'_>,
    base: &Path,
    errors: &mut Vec<FileError>,
) -> Option<usize> {
    let found = file
        .passes
        .iter()
        .position(|p| p.name.as_str() == name.as_str());
    if found.is_none() {
        let known: Vec<&str> = file.passes.iter().map(|p| p.name.as_str()).collect();
        errors.push(source.error(
            name,
            ErrorKind::UnknownPresetPass {
                pass: name.as_str().to_owned(),
                base: base.display().to_string(),
                known: known.join(", "),
            },
        ));
    }
    found
}

/// The parameters the graph file at `path` declares, with their defaults (a preset's
/// values for its base's), read without
/// declaring anything: what a tool checks before giving a value, as the bench does before
/// setting `msaa`. Errors are the file's syntax errors (or an unreadable file).
///
/// A preset's base is read as [`load_file`] reads it, inside the folders `registry` allows.
pub fn declared_params(
    path: impl AsRef<Path>,
    registry: &Registry,
) -> Result<GraphParams, FileErrors> {
    let path = path.as_ref();
    let text = read(path)?;
    let references = References::of_file(path, registry.roots(), &Folders::new());
    let arena = Arena::new();
    let (_, read) = read_graph(path, without_bom(&text), &arena, &references)?;
    Ok(param_uses::declared(&read.file).overridden_by(&read.values))
}

/// The text of the file at `path`, or the error saying why it cannot be read.
fn read(path: &Path) -> Result<String, FileErrors> {
    embedded::read_text(path, bounded_read::MAX_GRAPH_FILE_BYTES).map_err(|e| {
        FileErrors(vec![match e {
            ReadError::NotUtf8(e) => not_utf8(path, &e),
            e => FileError {
                location: Source::new(path, "").location(Position::START),
                kind: ErrorKind::Unreadable {
                    reason: e.to_string(),
                },
            },
        }])
    })
}

/// The error for a graph file at `path` that is not UTF-8, placed at its first bad byte.
fn not_utf8(path: &Path, error: &std::string::FromUtf8Error) -> FileError {
    let bytes = error.as_bytes();
    let valid = error.utf8_error().valid_up_to();
    // The bytes before the first bad one are valid UTF-8.
    let before = std::str::from_utf8(&bytes[..valid]).unwrap_or_default();
    let at = Position::of_offset(before, before.len());
    FileError {
        location: Source::new(path, "").location(at),
        kind: ErrorKind::NotUtf8 {
            detail: format!("byte 0x{:02X} cannot stand here", bytes[valid]),
        },
    }
}

/// Editors on Windows may start UTF-8 files with a byte-order mark, which `ron` reads as an
/// unexpected character. It is invisible in the editor, so columns do not count it.
fn without_bom(text: &str) -> &str {
    text.strip_prefix('\u{feff}').unwrap_or(text)
}

/// Each pass's plugin with its parameters, by file index (`None` where that failed).
fn prepare<'r>(
    source: &Source<'_>,
    file: &GraphFile<'_>,
    registry: &'r Registry,
    values: &GraphParams,
    errors: &mut Vec<FileError>,
) -> Vec<Option<Box<dyn Prepared + 'r>>> {
    file.passes
        .iter()
        .map(|pass| {
            let plugin_name = pass.plugin.as_str();
            let Some(plugin) = registry.get(plugin_name) else {
                let kind = ErrorKind::UnknownPlugin {
                    pass: pass.name.as_str().to_owned(),
                    plugin: plugin_name.to_owned(),
                    known: registry.names().collect::<Vec<_>>().join(", "),
                };
                errors.push(source.error(&pass.plugin, kind));
                return None;
            };
            // A pass without `params` gets `()`: plugins without parameters accept it,
            // others report their first missing field at the pass. Parameter uses become
            // their values, in text of the same length, so errors keep their places.
            let (text, base) = match &pass.params {
                Some(raw) => (
                    param_uses::substitute(raw.0.get_ron(), values),
                    Some(source.locate_raw(raw.0.get_ron())),
                ),
                None => ("()".to_owned(), None),
            };
            let text = text.as_str();
            plugin
                .prepare(text)
                .map_err(|e| {
                    let location = base.map_or_else(
                        || source.locate(&pass.name),
                        |base| Location {
                            at: Position::from(e.span.start)
                                .skip_whitespace(text)
                                .within(base.at),
                            ..base
                        },
                    );
                    errors.push(FileError {
                        location,
                        kind: ErrorKind::Params {
                            pass: pass.name.as_str().to_owned(),
                            plugin: plugin_name.to_owned(),
                            message: ron_message::describe(&e.code),
                        },
                    });
                })
                .ok()
        })
        .collect()
}
