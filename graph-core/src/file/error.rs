//! Errors in graph files: each one positioned (`FILE:LINE:COL`) and naming the pass and
//! the resource it is about, so a build log reads like a compiler's.

use std::fmt;
use std::path::Path;

use thiserror::Error;

use super::plugin_error::PluginError;
use crate::condition::ConditionError;
use crate::error::GraphError;
use crate::position::Position;

/// A position in a named file.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Location {
    /// The path as the caller gave it (relative paths stay relative).
    pub path: String,
    pub at: Position,
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}", self.path, self.at)
    }
}

/// What is wrong, in words that name the pass and resource involved.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum ErrorKind {
    #[error("cannot read the file: {reason}")]
    Unreadable { reason: String },

    /// Malformed RON, an unknown field, a value of the wrong type: `ron`'s message.
    #[error("{message}")]
    Syntax { message: String },

    #[error("resource \"{resource}\" is declared twice")]
    DuplicateResource { resource: String },

    #[error("two passes are called \"{pass}\"")]
    DuplicatePass { pass: String },

    #[error("pass \"{pass}\" lists slot \"{slot}\" twice in its {side}")]
    DuplicateSlot {
        pass: String,
        slot: String,
        side: &'static str,
    },

    #[error("pass \"{pass}\" uses plugin \"{plugin}\", which is not registered (known: {known})")]
    UnknownPlugin {
        pass: String,
        plugin: String,
        known: String,
    },

    /// A file the graph file names (`what`: "the preset's base") that it may not name:
    /// empty, absolute, or outside the folders graph files may reach. `reference` is shown
    /// quoted, control characters escaped; the file was not read.
    #[error("{what} {reference} {reason}")]
    Reference {
        what: &'static str,
        reference: String,
        reason: String,
    },

    /// Bytes that are not UTF-8, placed at the first of them.
    #[error("not UTF-8 text: {detail}; graph files are UTF-8")]
    NotUtf8 { detail: String },

    #[error("the preset's base {base} cannot be read: {reason}")]
    PresetBase { base: String, reason: String },

    #[error("the preset's base {base} is a preset too; a preset names a Graph file")]
    PresetOfPreset { base: String },

    #[error(
        "the preset changes pass \"{pass}\", which {base} does not have (its passes: {known})"
    )]
    UnknownPresetPass {
        pass: String,
        base: String,
        known: String,
    },

    #[error(
        "parameter \"{name}\" is given a value ({value}), but the file declares no parameter \
         of that name (it declares: {declared})"
    )]
    UnknownParam {
        name: String,
        value: u32,
        declared: String,
    },

    #[error(
        "parameter \"{name}\" has default {first} where it is first used and {second} here; \
         give every use the same default"
    )]
    ParamDefaults {
        name: String,
        first: u32,
        second: u32,
    },

    #[error(
        "parameter \"{name}\" is {value}, but the {field} of \"{resource}\" must be 1 or more"
    )]
    ParamValue {
        name: String,
        value: u32,
        resource: String,
        field: &'static str,
    },

    #[error("pass \"{pass}\": parameters of plugin \"{plugin}\": {message}")]
    Params {
        pass: String,
        plugin: String,
        message: String,
    },

    #[error("pass \"{pass}\" writes \"{resource}\", which is not declared in resources")]
    Undeclared { pass: String, resource: String },

    #[error(
        "pass \"{pass}\" names the version it writes \"{resource}\", which is a declared \
         resource; a modified version needs a new name"
    )]
    VersionNameTaken { pass: String, resource: String },

    #[error(
        "passes \"{first}\" and \"{second}\" both write \"{resource}\"; a name has one writer"
    )]
    TwoWriters {
        first: String,
        second: String,
        resource: String,
    },

    #[error(
        "passes \"{first}\" and \"{second}\" both modify \"{resource}\"; a version has one \
         writer (let \"{second}\" modify the version \"{first}\" writes)"
    )]
    ModifiedTwice {
        first: String,
        second: String,
        resource: String,
    },

    #[error(
        "pass \"{pass}\" reads \"{resource}\" and writes it too; to modify a resource, list \
         the slot in both inputs and outputs and give the new version a new name"
    )]
    SelfModify { pass: String, resource: String },

    #[error("output \"{resource}\" is not written by any pass")]
    UnwrittenOutput { resource: String },

    #[error(
        "output \"{resource}\" is not the final version: pass \"{pass}\" modifies it into \
         \"{next}\"; list \"{next}\" instead"
    )]
    OutputNotFinal {
        resource: String,
        pass: String,
        next: String,
    },

    #[error("{owner}: condition \"{condition}\": {error}")]
    BadCondition {
        /// `pass "NAME"` or `resource "NAME"`.
        owner: String,
        condition: String,
        error: ConditionError,
    },

    #[error("\"{feature}\" is not a feature name: {why}")]
    BadFeature { feature: String, why: String },

    #[error("feature \"{feature}\" is declared twice")]
    DuplicateFeature { feature: String },

    #[error(
        "passes \"{first}\" and \"{second}\" both write \"{resource}\" and their conditions \
         (\"{first_when}\", \"{second_when}\") are not exclusive; a name has one writer, or \
         one per exclusive condition"
    )]
    WritersNotExclusive {
        first: String,
        second: String,
        resource: String,
        first_when: String,
        second_when: String,
    },

    #[error("pass \"{pass}\" ({plugin}): {error}")]
    Plugin {
        pass: String,
        plugin: String,
        error: PluginError,
    },

    #[error(
        "pass \"{pass}\": plugin \"{plugin}\" has no use for slot \"{slot}\" (\"{resource}\")"
    )]
    UnusedSlot {
        pass: String,
        plugin: String,
        slot: String,
        resource: String,
    },

    /// Declaration and compile errors, the same as a graph built in code reports.
    #[error(transparent)]
    Graph(GraphError),

    /// A WGSL file that naga rejects (positioned in the shader itself).
    #[error("{message}")]
    Shader { message: String },
}

/// One positioned error.
#[derive(Debug, Clone, PartialEq, Error)]
#[error("{location}: error: {kind}")]
pub struct FileError {
    pub location: Location,
    pub kind: ErrorKind,
}

/// Every error found, in file order where there is one; displayed one per line.
#[derive(Debug, Clone, PartialEq, Error)]
#[error("{}", self.0.iter().map(|e| e.to_string()).collect::<Vec<_>>().join("\n"))]
pub struct FileErrors(pub Vec<FileError>);

impl FileErrors {
    /// Errors with the same location and message are reported once.
    pub(crate) fn sorted(mut errors: Vec<FileError>) -> FileErrors {
        errors.sort_by(|a, b| {
            (&a.location.path, a.location.at).cmp(&(&b.location.path, b.location.at))
        });
        errors.dedup();
        FileErrors(errors)
    }

    /// Whether `file` itself could not be read (missing, not a regular file, too large):
    /// an I/O problem for the caller, not a wrong file. Unreadable shaders the file names
    /// do not count: those are mistakes in the file.
    pub fn is_unreadable(&self, file: &Path) -> bool {
        self.0.iter().any(|e| {
            matches!(e.kind, ErrorKind::Unreadable { .. }) && Path::new(&e.location.path) == file
        })
    }
}
