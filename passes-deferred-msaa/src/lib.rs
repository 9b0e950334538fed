//! Deferred shading with MSAA as rgraph pass plugins, and the scenes they render.

pub mod scene;

use graph_core::file::Registry;

/// Adds this crate's pass plugins to `registry`, so graph files can name them.
pub fn register(registry: &mut Registry) {
    let _ = registry;
}
