//! The plugins the CLI knows: rgraph-core's generic ones and the deferred MSAA set, and the
//! folders `--graph-root` lets graph files reach.

use std::path::PathBuf;
use std::sync::{Arc, OnceLock};

use rgraph_core::file::Registry;
use rgraph_passes::variant::Variants;
use rgraph_passes::Host;

/// The command's `--graph-root` folders: set once, before any graph file is loaded, so
/// every registry the command makes (and loads graph files against) allows them.
static GRAPH_ROOTS: OnceLock<Vec<PathBuf>> = OnceLock::new();

/// Lets every graph file this run loads name files under `roots` too.
pub fn allow_graph_roots(roots: &[PathBuf]) {
    let _ = GRAPH_ROOTS.set(roots.to_vec());
}

/// For commands that only declare and compile: the deferred plugins draw nothing.
pub fn registry() -> Registry {
    registry_for(None, Variants::Scene)
}

/// With a host, the deferred plugins draw its scene with its overrides, compiling the
/// shader `variants`.
pub fn registry_for(host: Option<Arc<Host>>, variants: Variants) -> Registry {
    let mut registry = Registry::with_builtins();
    rgraph_passes::register_with(&mut registry, host, variants);
    for root in GRAPH_ROOTS.get().into_iter().flatten() {
        // The flag's parser checked that each is a folder; one removed since is left out,
        // and references into it are refused, naming the folders that are allowed.
        let _ = registry.allow_graph_root(root);
    }
    registry
}
