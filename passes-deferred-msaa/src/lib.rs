//! Deferred shading with MSAA as rgraph pass plugins, and the scenes they render.

pub mod host;
pub mod scene;

use std::sync::Arc;

use graph_core::file::Registry;

pub use host::{Host, Overrides};

/// Adds this crate's pass plugins to `registry`, so graph files can name them. With
/// `host: None` the plugins declare and validate passes but draw nothing (see [`host`]).
pub fn register(registry: &mut Registry, host: Option<Arc<Host>>) {
    let _ = (registry, host);
}
