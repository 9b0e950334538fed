//! Why a plugin could not set up its pass: what slots, plugins and the loader share.

use thiserror::Error;

use super::shown::Shown;
use crate::shader::{ShaderError, Stage};

/// Why a plugin could not set up its pass. The loader adds the file position, the pass
/// and the plugin name; messages here name the slot and the resource in it.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum PluginError {
    #[error("needs slot \"{slot}\" in its {side}")]
    MissingSlot { slot: String, side: &'static str },

    #[error("writes slot \"{slot}\" (\"{resource}\"), so the slot belongs in outputs")]
    NotAnOutput { slot: String, resource: String },

    #[error("only reads slot \"{slot}\" (\"{resource}\"), so the slot belongs in inputs only")]
    NotAnInput { slot: String, resource: String },

    #[error("slot \"{slot}\" holds {found} \"{resource}\", but needs a {expected}")]
    SlotKind {
        slot: String,
        resource: String,
        found: &'static str,
        expected: &'static str,
    },

    #[error("slot \"{slot}\": \"{resource}\" {why}")]
    Slot {
        slot: String,
        resource: String,
        why: String,
    },

    #[error(transparent)]
    Shader(#[from] ShaderError),

    #[error("shader \"{shader}\" has no {stage} entry point \"{entry}\" (it has: {found})")]
    MissingEntry {
        shader: String,
        stage: Stage,
        entry: String,
        found: String,
    },

    /// A binding the file declares and the shader disagree; `slot` is the file's slot
    /// bound there, if any.
    #[error("shader \"{shader}\" @group({group}) @binding({binding}): {why}")]
    Binding {
        shader: String,
        group: u32,
        binding: u32,
        slot: Option<String>,
        why: String,
    },

    /// A file the parameters name (`what`: "shader") that the graph file may not name:
    /// empty, absolute, or outside the folders graph files may reach. The file was not read.
    #[error("{what} {} {reason}", Shown(reference))]
    Reference {
        what: &'static str,
        reference: String,
        reason: String,
    },

    /// Parameters that deserialize but do not make sense together.
    #[error("{0}")]
    Invalid(String),
}

impl PluginError {
    /// The slot the error is about, so the loader can point at it.
    pub fn slot(&self) -> Option<&str> {
        match self {
            PluginError::NotAnOutput { slot, .. }
            | PluginError::NotAnInput { slot, .. }
            | PluginError::SlotKind { slot, .. }
            | PluginError::Slot { slot, .. } => Some(slot),
            PluginError::Binding { slot, .. } => slot.as_deref(),
            PluginError::MissingSlot { .. }
            | PluginError::Shader(_)
            | PluginError::MissingEntry { .. }
            | PluginError::Reference { .. }
            | PluginError::Invalid(_) => None,
        }
    }

    /// The file reference the error is about, as written in the parameters, so the
    /// loader can point at it.
    pub fn reference(&self) -> Option<&str> {
        match self {
            PluginError::Reference { reference, .. } => Some(reference),
            _ => None,
        }
    }
}
