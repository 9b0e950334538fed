//! The plugins the CLI knows: graph-core's generic ones and the deferred MSAA set.

use graph_core::file::Registry;

pub fn registry() -> Registry {
    let mut registry = Registry::with_builtins();
    passes_deferred_msaa::register(&mut registry, None);
    registry
}
