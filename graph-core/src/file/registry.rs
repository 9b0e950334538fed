//! The plugins graph files can name.

use std::collections::BTreeMap;

use super::plugin::{AnyPlugin, Plugin};

/// Plugins by name. Build scripts, the CLI and engines each make one, add their own
/// plugins, and load graph files against it.
#[derive(Default)]
pub struct Registry {
    plugins: BTreeMap<&'static str, Box<dyn AnyPlugin>>,
}

impl Registry {
    /// A registry without plugins.
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds `plugin` under [`Plugin::NAME`], replacing a plugin of the same name (so an
    /// engine can override a built-in).
    pub fn register<P: Plugin>(&mut self, plugin: P) -> &mut Self {
        self.plugins.insert(P::NAME, Box::new(plugin));
        self
    }

    /// The registered names, sorted.
    pub fn names(&self) -> impl Iterator<Item = &'static str> + '_ {
        self.plugins.keys().copied()
    }

    pub(crate) fn get(&self, name: &str) -> Option<&dyn AnyPlugin> {
        self.plugins.get(name).map(|p| p.as_ref())
    }
}
