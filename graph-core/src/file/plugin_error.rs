//! Why a plugin could not set up its pass: what slots, plugins and the loader share.

use thiserror::Error;

use super::shown::Shown;
use crate::shader::{ShaderError, Stage};

/// Why a plugin could not set up its pass. The loader adds the file position, the pass
/// and the plugin name; messages here name the slot and the resource in it.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum PluginError {
    /// The pass does not bind a slot the plugin needs.
    #[error("needs slot \"{slot}\" in its {side}")]
    MissingSlot {
        /// The slot, as the plugin names it.
        slot: String,
        /// `inputs` or `outputs`.
        side: &'static str,
    },

    /// The plugin writes a slot the file lists only in inputs.
    #[error("writes slot \"{slot}\" (\"{resource}\"), so the slot belongs in outputs")]
    NotAnOutput {
        /// The slot, as the plugin names it.
        slot: String,
        /// The resource the file binds to the slot.
        resource: String,
    },

    /// The plugin only reads a slot the file lists in outputs.
    #[error("only reads slot \"{slot}\" (\"{resource}\"), so the slot belongs in inputs only")]
    NotAnInput {
        /// The slot, as the plugin names it.
        slot: String,
        /// The resource the file binds to the slot.
        resource: String,
    },

    /// A slot holds a texture where the plugin needs a buffer, or the other way round.
    #[error("slot \"{slot}\" holds {found} \"{resource}\", but needs a {expected}")]
    SlotKind {
        /// The slot, as the plugin names it.
        slot: String,
        /// The resource the file binds to the slot.
        resource: String,
        /// What the slot holds: "texture" or "buffer".
        found: &'static str,
        /// What the plugin needs there.
        expected: &'static str,
    },

    /// The resource in a slot does not fit the plugin (its format, size or samples).
    #[error("slot \"{slot}\": \"{resource}\" {why}")]
    Slot {
        /// The slot, as the plugin names it.
        slot: String,
        /// The resource the file binds to the slot.
        resource: String,
        /// What is wrong, in words.
        why: String,
    },

    /// A shader the parameters name does not read, parse or validate.
    #[error(transparent)]
    Shader(#[from] ShaderError),

    /// A shader lacks the entry point the parameters name.
    #[error("shader \"{shader}\" has no {stage} entry point \"{entry}\" (it has: {found})")]
    MissingEntry {
        /// The shader file, as the parameters name it.
        shader: String,
        /// The stage the entry point is for.
        stage: Stage,
        /// The entry point asked for.
        entry: String,
        /// The shader's entry points of that stage, comma-separated.
        found: String,
    },

    /// A binding the file declares and the shader disagree; `slot` is the file's slot
    /// bound there, if any.
    #[error("shader \"{shader}\" @group({group}) @binding({binding}): {why}")]
    Binding {
        /// The shader file, as the parameters name it.
        shader: String,
        /// `@group` of the binding.
        group: u32,
        /// `@binding` of the binding.
        binding: u32,
        /// The slot, as the plugin names it.
        slot: Option<String>,
        /// What is wrong, in words.
        why: String,
    },

    /// A file the parameters name (`what`: "shader") that the graph file may not name:
    /// empty, absolute, or outside the folders graph files may reach. The file was not read.
    #[error("{what} {} {reason}", Shown(reference))]
    Reference {
        /// What the parameters name: "shader".
        what: &'static str,
        /// The name as written.
        reference: String,
        /// Why it may not be named.
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
