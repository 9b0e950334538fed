//! Looking up the entry point a graph file names, as a plugin error when it is missing.

use crate::file::PluginError;
use crate::shader::{Entry, Shader, Stage};

/// The `stage` entry point `name` of `shader`; the error lists the ones it has.
pub(crate) fn entry_point<'s>(
    shader: &'s Shader,
    name: &str,
    stage: Stage,
) -> Result<Entry<'s>, PluginError> {
    shader
        .entry(name, stage)
        .ok_or_else(|| PluginError::MissingEntry {
            shader: shader.path().to_owned(),
            stage,
            entry: name.to_owned(),
            found: shader.entry_names(stage).join(", "),
        })
}
