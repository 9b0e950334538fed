//! The plugins the CLI knows: graph-core's generic ones and the deferred MSAA set.

use std::sync::Arc;

use graph_core::file::Registry;
use passes_deferred_msaa::Host;

/// For commands that only declare and compile: the deferred plugins draw nothing.
pub fn registry() -> Registry {
    registry_for(None)
}

/// With a host, the deferred plugins draw its scene with its overrides.
pub fn registry_for(host: Option<Arc<Host>>) -> Registry {
    let mut registry = Registry::with_builtins();
    passes_deferred_msaa::register(&mut registry, host);
    registry
}
