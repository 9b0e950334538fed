//! The plugins the CLI knows: graph-core's generic ones and the deferred MSAA set.

use std::sync::Arc;

use graph_core::file::Registry;
use passes_deferred_msaa::analysis::Variants;
use passes_deferred_msaa::Host;

/// For commands that only declare and compile: the deferred plugins draw nothing.
pub fn registry() -> Registry {
    registry_for(None, Variants::Scene)
}

/// With a host, the deferred plugins draw its scene with its overrides, compiling the
/// shader `variants`.
pub fn registry_for(host: Option<Arc<Host>>, variants: Variants) -> Registry {
    let mut registry = Registry::with_builtins();
    passes_deferred_msaa::register_with(&mut registry, host, variants);
    registry
}
