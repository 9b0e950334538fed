//! Pass plugins: what a graph file's `plugin: "name"` stands for.

use serde::de::DeserializeOwned;
use thiserror::Error;

use super::schema;
use super::slots::Slots;
use crate::builder::PassBuilder;
use crate::pass::PassKind;
use crate::shader::{ShaderError, Stage};

/// A pass type that graph files can name. The loader deserializes the pass's `params`
/// into [`Plugin::Params`], begins a pass of [`Plugin::kind`] named as in the file, and
/// calls [`Plugin::setup`] with the handles for the slots the file declares.
///
/// `setup` declares the pass's accesses on `pass` through those handles, exactly as code
/// would, and (with feature `gpu`) its record callback; it must take every slot the file
/// lists through `slots` (unused slots are errors) and must not panic on any parameters.
pub trait Plugin: 'static {
    /// The name graph files use.
    const NAME: &'static str;
    /// The parameters; use `#[serde(deny_unknown_fields)]` so misspelled fields are errors.
    type Params: DeserializeOwned;

    fn kind(&self, params: &Self::Params) -> PassKind;

    fn setup(
        &self,
        params: Self::Params,
        pass: &mut PassBuilder<'_>,
        slots: &mut Slots<'_>,
    ) -> Result<(), PluginError>;
}

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
            | PluginError::Invalid(_) => None,
        }
    }
}

/// A plugin without its parameter type, as the registry keeps it.
pub(crate) trait AnyPlugin {
    /// Deserializes `params` (RON text) for this plugin.
    fn prepare(&self, params: &str) -> Result<Box<dyn Prepared + '_>, ron::error::SpannedError>;
}

/// A plugin with its parameters, ready to set up one pass.
pub(crate) trait Prepared {
    fn kind(&self) -> PassKind;
    fn setup(
        self: Box<Self>,
        pass: &mut PassBuilder<'_>,
        slots: &mut Slots<'_>,
    ) -> Result<(), PluginError>;
}

impl<P: Plugin> AnyPlugin for P {
    fn prepare(&self, params: &str) -> Result<Box<dyn Prepared + '_>, ron::error::SpannedError> {
        let params = schema::options().from_str::<P::Params>(params)?;
        Ok(Box::new(Ready {
            plugin: self,
            params,
        }))
    }
}

struct Ready<'p, P: Plugin> {
    plugin: &'p P,
    params: P::Params,
}

impl<P: Plugin> Prepared for Ready<'_, P> {
    fn kind(&self) -> PassKind {
        self.plugin.kind(&self.params)
    }

    fn setup(
        self: Box<Self>,
        pass: &mut PassBuilder<'_>,
        slots: &mut Slots<'_>,
    ) -> Result<(), PluginError> {
        self.plugin.setup(self.params, pass, slots)
    }
}
