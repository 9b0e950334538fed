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
    /// Line and column (1-based) in that file.
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
    /// The file could not be read: missing, not a regular file, larger than the bounded
    /// read allows.
    #[error("cannot read the file: {reason}")]
    Unreadable {
        /// Why, in words (the operating system's message for I/O).
        reason: String,
    },

    /// Malformed RON, an unknown field, a value of the wrong type: `ron`'s message.
    #[error("{message}")]
    Syntax {
        /// The parser's message.
        message: String,
    },

    /// Two resources of one name.
    #[error("resource \"{resource}\" is declared twice")]
    DuplicateResource {
        /// The resource or version, by name.
        resource: String,
    },

    /// Two passes of one name.
    #[error("two passes are called \"{pass}\"")]
    DuplicatePass {
        /// The pass, by name.
        pass: String,
    },

    /// A pass lists a slot twice on one side.
    #[error("pass \"{pass}\" lists slot \"{slot}\" twice in its {side}")]
    DuplicateSlot {
        /// The pass, by name.
        pass: String,
        /// The slot name.
        slot: String,
        /// `inputs` or `outputs`.
        side: &'static str,
    },

    /// A pass names a plugin the registry does not have.
    #[error("pass \"{pass}\" uses plugin \"{plugin}\", which is not registered (known: {known})")]
    UnknownPlugin {
        /// The pass, by name.
        pass: String,
        /// The plugin the pass names.
        plugin: String,
        /// What the file or registry does have, comma-separated.
        known: String,
    },

    /// A file the graph file names (`what`: "the preset's base") that it may not name:
    /// empty, absolute, or outside the folders graph files may reach. `reference` is shown
    /// quoted, control characters escaped; the file was not read.
    #[error("{what} {reference} {reason}")]
    Reference {
        /// What the file names: "the preset's base", "the shader".
        what: &'static str,
        /// The name as written, quoted.
        reference: String,
        /// Why, in words (the operating system's message for I/O).
        reason: String,
    },

    /// Bytes that are not UTF-8, placed at the first of them.
    #[error("not UTF-8 text: {detail}; graph files are UTF-8")]
    NotUtf8 {
        /// Where the first invalid byte is.
        detail: String,
    },

    /// A preset's base file cannot be read.
    #[error("the preset's base {base} cannot be read: {reason}")]
    PresetBase {
        /// The preset's base file, quoted as written.
        base: String,
        /// Why, in words (the operating system's message for I/O).
        reason: String,
    },

    /// A preset's base is itself a preset; presets do not chain.
    #[error("the preset's base {base} is a preset too; a preset names a Graph file")]
    PresetOfPreset {
        /// The preset's base file, quoted as written.
        base: String,
    },

    /// A preset changes a pass its base does not have.
    #[error(
        "the preset changes pass \"{pass}\", which {base} does not have (its passes: {known})"
    )]
    UnknownPresetPass {
        /// The pass, by name.
        pass: String,
        /// The preset's base file, quoted as written.
        base: String,
        /// What the file or registry does have, comma-separated.
        known: String,
    },

    /// A `passes` entry that is neither a pass nor a use of a part, or mixes the two.
    #[error("{message}")]
    EntryShape {
        /// What is wrong, naming the fields.
        message: String,
    },

    /// Parts that use parts grow the graph past the limit.
    #[error("the graph grows past {limit} passes and part uses through its parts")]
    TooManyEntries {
        /// The most passes and uses a graph may have.
        limit: usize,
    },

    /// A use names a file that is not a part.
    #[error("{part} is {kind}, not a part; a use names a `Part(..)` file")]
    NotAPart {
        /// The file, as the use resolves it.
        part: String,
        /// What it is instead: "a graph file", "a preset".
        kind: &'static str,
    },

    /// A part that uses itself, directly or through others.
    #[error("parts use each other in a cycle: {chain} (the cycle's first use is at {first})")]
    PartCycle {
        /// The part files of the cycle, "a uses b uses a".
        chain: String,
        /// Where the first part of the cycle is used.
        first: Location,
    },

    /// Two uses of one part under the same prefix: their names would collide.
    #[error(
        "part {part} is used again with prefix \"{prefix}\" (first at {first}); give each use \
         a `prefix` of its own"
    )]
    PartTwice {
        /// The part file.
        part: String,
        /// The prefix both uses give its names.
        prefix: String,
        /// Where the first use is.
        first: Location,
    },

    /// A part names a feature the graph using it does not declare.
    #[error(
        "part {part} needs feature \"{feature}\" ({at}), which this graph does not declare \
         (it declares: {declared})"
    )]
    PartFeature {
        /// The part file.
        part: String,
        /// The feature.
        feature: String,
        /// Where the part names it.
        at: Location,
        /// The graph's features, comma-separated.
        declared: String,
    },

    /// A use's condition names a feature the graph does not declare.
    #[error(
        "the use of part {part} is under feature \"{feature}\", which this graph does not \
         declare (it declares: {declared})"
    )]
    UseFeature {
        /// The part file.
        part: String,
        /// The feature.
        feature: String,
        /// The graph's features, comma-separated.
        declared: String,
    },

    /// A use binds a slot the part does not have.
    #[error("part {part} {side} no \"{slot}\" (it {side}: {known})")]
    PartNoSlot {
        /// The part file.
        part: String,
        /// "takes" (a use's inputs) or "gives" (its outputs).
        side: &'static str,
        /// The slot the use binds.
        slot: String,
        /// The part's slots on that side, comma-separated.
        known: String,
    },

    /// A use gives a value to a parameter its part does not use.
    #[error("part {part} has no parameter \"{name}\" (its parameters: {declared})")]
    PartParam {
        /// The part file.
        part: String,
        /// The parameter the use names.
        name: String,
        /// The parameters the part uses, comma-separated.
        declared: String,
    },

    /// A use leaves a resource the part takes unbound, and the graph has none of its name.
    #[error(
        "this use of part {part} binds nothing to \"{slot}\", which the part takes ({at}), \
         and the graph has no \"{slot}\" to bind by name"
    )]
    PartUnbound {
        /// The part file.
        part: String,
        /// The slot.
        slot: String,
        /// Where the part's interface declares it.
        at: Location,
    },

    /// A slot of a use holds a resource unlike the part's interface says.
    #[error(
        "part {part} {side} \"{slot}\" as {wanted} ({at}), but in this use it is \
         \"{bound}\", {found}"
    )]
    PartBinding {
        /// The part file.
        part: String,
        /// "takes" or "gives".
        side: &'static str,
        /// The slot.
        slot: String,
        /// What the interface asks for, in words.
        wanted: String,
        /// Where the part's interface declares the slot.
        at: Location,
        /// The version the use binds.
        bound: String,
        /// What that version is, in words.
        found: String,
    },

    /// A preset rebinds a name its base does not have.
    #[error("the preset rebinds \"{name}\", which {base} neither declares nor writes")]
    UnknownRebind {
        /// The name.
        name: String,
        /// The preset's base file.
        base: String,
    },

    /// The caller gives a value to a parameter the file does not declare.
    #[error(
        "parameter \"{name}\" is given a value ({value}), but the file declares no parameter \
         of that name (it declares: {declared})"
    )]
    UnknownParam {
        /// The parameter's name.
        name: String,
        /// The value given.
        value: u32,
        /// The parameters the file declares, comma-separated.
        declared: String,
    },

    /// Two uses of one parameter give it different defaults.
    #[error(
        "parameter \"{name}\" has default {first} where it is first used and {second} here; \
         give every use the same default"
    )]
    ParamDefaults {
        /// The parameter's name.
        name: String,
        /// The default where it is first used.
        first: u32,
        /// The default here.
        second: u32,
    },

    /// A parameter's value is not valid where it is used (0 samples, say).
    #[error(
        "parameter \"{name}\" is {value}, but the {field} of \"{resource}\" must be 1 or more"
    )]
    ParamValue {
        /// The parameter's name.
        name: String,
        /// The parameter's value.
        value: u32,
        /// The resource or version, by name.
        resource: String,
        /// The resource field it sets (`samples`, `mips`, ...).
        field: &'static str,
    },

    /// A pass's `params` do not fit its plugin's parameters.
    #[error("pass \"{pass}\": parameters of plugin \"{plugin}\": {message}")]
    Params {
        /// The pass, by name.
        pass: String,
        /// The plugin the pass names.
        plugin: String,
        /// The deserializer's message.
        message: String,
    },

    /// A pass writes, through an output slot that is not also an input (no modification),
    /// a name not declared in `resources`.
    #[error("pass \"{pass}\" writes \"{resource}\", which is not declared in resources")]
    Undeclared {
        /// The pass, by name.
        pass: String,
        /// The resource or version, by name.
        resource: String,
    },

    /// A pass gives the version it writes the name of a declared resource.
    #[error(
        "pass \"{pass}\" names the version it writes \"{resource}\", which is a declared \
         resource; a modified version needs a new name"
    )]
    VersionNameTaken {
        /// The pass, by name.
        pass: String,
        /// The resource or version, by name.
        resource: String,
    },

    /// Two passes write one name (without exclusive conditions).
    #[error(
        "passes \"{first}\" and \"{second}\" both write \"{resource}\"; a name has one writer"
    )]
    TwoWriters {
        /// The pass written first in the file.
        first: String,
        /// The pass written second.
        second: String,
        /// The resource or version, by name.
        resource: String,
    },

    /// Two passes modify the same version of a resource.
    #[error(
        "passes \"{first}\" and \"{second}\" both modify \"{resource}\"; a version has one \
         writer (let \"{second}\" modify the version \"{first}\" writes)"
    )]
    ModifiedTwice {
        /// The pass written first in the file.
        first: String,
        /// The pass written second.
        second: String,
        /// The resource or version, by name.
        resource: String,
    },

    /// A pass lists the same name as an input and as an output.
    #[error(
        "pass \"{pass}\" reads \"{resource}\" and writes it too; to modify a resource, list \
         the slot in both inputs and outputs and give the new version a new name"
    )]
    SelfModify {
        /// The pass, by name.
        pass: String,
        /// The resource or version, by name.
        resource: String,
    },

    /// A graph output that no pass writes.
    #[error("output \"{resource}\" is not written by any pass")]
    UnwrittenOutput {
        /// The resource or version, by name.
        resource: String,
    },

    /// A graph output that a later pass modifies into another version.
    #[error(
        "output \"{resource}\" is not the final version: pass \"{pass}\" modifies it into \
         \"{next}\"; list \"{next}\" instead"
    )]
    OutputNotFinal {
        /// The resource or version, by name.
        resource: String,
        /// The pass that modifies it.
        pass: String,
        /// The name of the later version.
        next: String,
    },

    /// A `when` condition that does not parse.
    #[error("{owner}: condition \"{condition}\": {error}")]
    BadCondition {
        /// `pass "NAME"` or `resource "NAME"`.
        owner: String,
        /// The condition as written.
        condition: String,
        /// The underlying error.
        error: ConditionError,
    },

    /// A declared feature name that is not a valid name.
    #[error("\"{feature}\" is not a feature name: {why}")]
    BadFeature {
        /// The feature name, as written.
        feature: String,
        /// What is wrong with it.
        why: String,
    },

    /// A feature declared twice.
    #[error("feature \"{feature}\" is declared twice")]
    DuplicateFeature {
        /// The feature name, as written.
        feature: String,
    },

    /// Two passes write one name and their conditions can hold together.
    #[error(
        "passes \"{first}\" and \"{second}\" both write \"{resource}\" and their conditions \
         (\"{first_when}\", \"{second_when}\") are not exclusive; a name has one writer, or \
         one per exclusive condition"
    )]
    WritersNotExclusive {
        /// The pass written first in the file.
        first: String,
        /// The pass written second.
        second: String,
        /// The resource or version, by name.
        resource: String,
        /// The first pass's condition.
        first_when: String,
        /// The second pass's condition.
        second_when: String,
    },

    /// A plugin refused the pass at setup: its slots, parameters or resources do not fit.
    #[error("pass \"{pass}\" ({plugin}): {error}")]
    Plugin {
        /// The pass, by name.
        pass: String,
        /// The plugin the pass names.
        plugin: String,
        /// The underlying error.
        error: PluginError,
    },

    /// A pass binds a slot its plugin does not use.
    #[error(
        "pass \"{pass}\": plugin \"{plugin}\" has no use for slot \"{slot}\" (\"{resource}\")"
    )]
    UnusedSlot {
        /// The pass, by name.
        pass: String,
        /// The plugin the pass names.
        plugin: String,
        /// The slot name.
        slot: String,
        /// The resource bound to it.
        resource: String,
    },

    /// A pass's `optional` names a slot that is neither one of its input-only slots nor
    /// one of its output-only slots.
    #[error("pass \"{pass}\": optional slot \"{slot}\" {why}")]
    OptionalSlot {
        /// The pass, by name.
        pass: String,
        /// The slot name.
        slot: String,
        /// "is not one of its inputs or outputs", "is in its inputs and outputs: a
        /// modification cannot be optional".
        why: String,
    },

    /// Declaration and compile errors, the same as a graph built in code reports.
    #[error(transparent)]
    Graph(GraphError),

    /// A WGSL file that naga rejects (positioned in the shader itself).
    #[error("{message}")]
    Shader {
        /// naga's message, positioned in the shader.
        message: String,
    },
}

/// One positioned error.
#[derive(Debug, Clone, PartialEq, Error)]
#[error("{location}: error: {kind}")]
pub struct FileError {
    /// Where: the file and the line and column the error points at.
    pub location: Location,
    /// What is wrong.
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
