//! The plugins graph files can name, and the folders the files they name may lie in.

use std::collections::BTreeMap;
use std::path::Path;

use super::plugin::{AnyPlugin, Plugin};
use crate::folders::Folders;

/// Plugins by name, and the folders graph files may name files in besides their own.
/// Build scripts, the CLI and engines each make one, add their own plugins (and folders),
/// and load graph files against it.
///
/// A graph file's references (a preset's `base`, a pass's `shader`) must stay inside the
/// graph file's own folder, the folders of the program's built-in files (see
/// [`embedded`](crate::embedded): the shipped `pipelines/` and `shaders/`), and the folders
/// added with [`allow_graph_root`](Self::allow_graph_root); anything else is an error naming
/// the reference, and the file is never read.
#[derive(Default)]
pub struct Registry {
    plugins: BTreeMap<&'static str, Box<dyn AnyPlugin>>,
    roots: Folders,
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

    /// Lets graph files loaded against this registry name files under `dir` too (the CLI's
    /// `--graph-root`): an engine's shared shaders, say. Fails when `dir` is not a folder
    /// that exists.
    pub fn allow_graph_root(&mut self, dir: impl AsRef<Path>) -> std::io::Result<&mut Self> {
        self.roots.allow(dir.as_ref())?;
        Ok(self)
    }

    /// The folders added with [`allow_graph_root`](Self::allow_graph_root).
    pub(crate) fn roots(&self) -> &Folders {
        &self.roots
    }

    /// The registered names, sorted.
    pub fn names(&self) -> impl Iterator<Item = &'static str> + '_ {
        self.plugins.keys().copied()
    }

    pub(crate) fn get(&self, name: &str) -> Option<&dyn AnyPlugin> {
        self.plugins.get(name).map(|p| p.as_ref())
    }
}
