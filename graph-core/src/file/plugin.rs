//! Pass plugins: what a graph file's `plugin: "name"` stands for.

use serde::de::DeserializeOwned;

use super::plugin_error::PluginError;
use super::schema;
use super::slots::Slots;
use crate::builder::PassBuilder;
use crate::pass::PassKind;

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

    /// The kind of pass the plugin records for `params` (a plugin may record a render or
    /// a compute pass depending on its parameters).
    fn kind(&self, params: &Self::Params) -> PassKind;

    /// Declares the pass: takes every slot the file lists from `slots`, declares the
    /// accesses on `pass` and (feature `gpu`) its record callback. An error refuses the
    /// pass and names the slot or parameter at fault; the graph is not loaded.
    fn setup(
        &self,
        params: Self::Params,
        pass: &mut PassBuilder<'_>,
        slots: &mut Slots<'_>,
    ) -> Result<(), PluginError>;
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
