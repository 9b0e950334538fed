//! Plugin passes declared from code: an engine adds the same passes a graph file names,
//! with the same checks, next to passes it writes itself.

use std::path::Path;

use thiserror::Error;

use super::any_handle::AnyHandle;
use super::plugin::Plugin;
use super::plugin_error::PluginError;
use super::references::References;
use super::slots::{SlotPart, Slots};
use crate::builder::GraphBuilder;
use crate::handle::{BufferHandle, TextureHandle};
use crate::pass::PassKind;

/// A plugin pass that could not be declared, with the pass and plugin it concerns.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum PluginPassError {
    /// The plugin refused the pass: its slots, parameters or resources do not fit.
    #[error("pass \"{pass}\" (plugin \"{plugin}\"): {error}")]
    Setup {
        /// The pass, by name.
        pass: String,
        /// The plugin's name.
        plugin: &'static str,
        // Boxed: plugin errors are large, and results of this type are returned often.
        /// The plugin's reason.
        error: Box<PluginError>,
    },

    /// A slot was bound that the plugin does not use.
    #[error(
        "pass \"{pass}\": plugin \"{plugin}\" has no use for slot \"{slot}\" (\"{resource}\")"
    )]
    UnusedSlot {
        /// The pass, by name.
        pass: String,
        /// The plugin's name.
        plugin: &'static str,
        /// The slot's name.
        slot: String,
        /// The resource bound to it.
        resource: String,
    },
}

/// The versions a plugin pass wrote, by output slot.
#[derive(Clone, Debug, Default)]
pub struct Written(Vec<(String, AnyHandle)>);

impl Written {
    /// The version written to `slot`, of either kind; `None` when the plugin wrote
    /// nothing there.
    pub fn get(&self, slot: &str) -> Option<AnyHandle> {
        self.0.iter().find(|(s, _)| s == slot).map(|(_, h)| *h)
    }

    /// The texture version written to `slot`, if the plugin wrote a texture there.
    pub fn texture(&self, slot: &str) -> Option<TextureHandle> {
        self.get(slot).and_then(|h| h.typed())
    }

    /// The buffer version written to `slot`, if the plugin wrote a buffer there.
    pub fn buffer(&self, slot: &str) -> Option<BufferHandle> {
        self.get(slot).and_then(|h| h.typed())
    }
}

impl GraphBuilder {
    /// Declares a pass of `plugin`, as a graph file's `(name, plugin, params, inputs,
    /// outputs)` would. `inputs` and `outputs` pair the plugin's slot names with handles:
    /// an input's handle is the version read; an output's is the resource written, and a
    /// slot listed in both modifies the version it reads. Shader paths in `params`
    /// resolve against the current directory.
    ///
    /// Returns the new versions by output slot. After an error the builder holds a
    /// partly declared pass: report the error and drop the builder.
    pub fn add_plugin_pass<P: Plugin>(
        &mut self,
        name: impl Into<String>,
        plugin: &P,
        params: P::Params,
        inputs: &[(&str, AnyHandle)],
        outputs: &[(&str, AnyHandle)],
    ) -> Result<Written, PluginPassError> {
        let name = name.into();
        let resource_names: Vec<String> = outputs
            .iter()
            .chain(inputs)
            .map(|(_, h)| self.resources[h.id().index()].name.clone())
            .collect();
        let (output_names, input_names) = resource_names.split_at(outputs.len());
        let input = |slot: &str| {
            let at = inputs.iter().position(|(s, _)| *s == slot)?;
            Some((input_names[at].as_str(), inputs[at].1))
        };
        let written = outputs
            .iter()
            .zip(output_names)
            .map(|(&(slot, handle), out)| {
                let read = input(slot);
                SlotPart {
                    name: slot,
                    input: read.map(|(n, _)| n),
                    output: Some(out.as_str()),
                    handle: read.map_or(handle, |(_, h)| h),
                    optional: false,
                }
            });
        let read_only = inputs
            .iter()
            .zip(input_names)
            .filter(|((slot, _), _)| outputs.iter().all(|(s, _)| s != slot))
            .map(|(&(slot, handle), read)| SlotPart {
                name: slot,
                input: Some(read.as_str()),
                output: None,
                handle,
                optional: false,
            });
        let references = References::unrestricted();
        let parts = written.chain(read_only).collect();
        let mut slots = Slots::from_parts(parts, Path::new("."), &references);

        let kind = plugin.kind(&params);
        let mut pass = match kind {
            PassKind::Render => self.add_render_pass(name.clone()),
            PassKind::Compute => self.add_compute_pass(name.clone()),
            PassKind::Transfer => self.add_transfer_pass(name.clone()),
        };
        plugin
            .setup(params, &mut pass, &mut slots)
            .map_err(|error| PluginPassError::Setup {
                pass: name.clone(),
                plugin: P::NAME,
                error: Box::new(error),
            })?;
        let finished = slots.finish();
        if let Some((slot, resource)) = finished.unused.first() {
            return Err(PluginPassError::UnusedSlot {
                pass: name,
                plugin: P::NAME,
                slot: (*slot).to_owned(),
                resource: (*resource).to_owned(),
            });
        }
        Ok(Written(
            finished
                .written
                .into_iter()
                .map(|(slot, _, handle)| (slot.to_owned(), handle))
                .collect(),
        ))
    }
}
