//! What every deferred plugin of one registry shares ([`Shared`]), and how a pass set up
//! in `Plugin::setup` becomes its record callback ([`Recording`]).

use std::sync::Arc;

use graph_core::PassBuilder;

use crate::host::{Host, Overrides};
use crate::variant::Variants;

/// What every plugin of one registry shares: the host's overrides and, with feature
/// `gpu`, the scene's upload.
#[derive(Clone)]
pub(crate) struct Shared {
    pub overrides: Overrides,
    /// A host gave a scene, so passes may read its group 0 (the tone mapper reads the
    /// frame's exposure there).
    pub draws_scene: bool,
    #[cfg(feature = "gpu")]
    pub scenes: Arc<crate::gpu_scene::SceneCache>,
}

impl Shared {
    #[cfg_attr(not(feature = "gpu"), allow(unused_variables))]
    pub fn new(host: Option<Arc<Host>>, variants: Variants) -> Shared {
        Shared {
            overrides: host
                .as_ref()
                .map(|h| h.overrides.clone())
                .unwrap_or_default(),
            draws_scene: host.is_some(),
            #[cfg(feature = "gpu")]
            scenes: Arc::new(crate::gpu_scene::SceneCache::new(host, variants)),
        }
    }

    /// Gives the pass its record callback. Without feature `gpu` graphs are only declared
    /// and validated, and `recording` is dropped.
    pub fn record(&self, pass: &mut PassBuilder<'_>, recording: impl Recording) {
        #[cfg(feature = "gpu")]
        match recording.record(self.scenes.clone()) {
            graph_core::Record::Render(record) => pass.render(record),
            graph_core::Record::Compute(record) => pass.compute(record),
            graph_core::Record::Transfer(record) => pass.transfer(record),
        }
        #[cfg(not(feature = "gpu"))]
        let _ = (pass, recording);
    }
}

/// A pass as its plugin set it up, ready to be recorded on a device: its record
/// callback, of the kind the plugin declared the pass.
pub(crate) trait Recording: 'static {
    #[cfg(feature = "gpu")]
    fn record(self, scenes: Arc<crate::gpu_scene::SceneCache>) -> graph_core::Record;
}

/// Why `edge_stencil` and `light_edge` leave themselves out of plans with one sample
/// per pixel (`PassBuilder::omit`).
pub(crate) const ONE_SAMPLE: &str = "one sample per pixel: a pixel holds one surface, so \
                                     there are no edge pixels to find or to shade per sample";

/// `true`, for `#[serde(default = "yes")]`.
pub(crate) fn yes() -> bool {
    true
}

/// Checks a tiled pass's `tile` parameter (pixels per tile side) against the sides it
/// allows.
pub(crate) fn check_tile(
    tile: u32,
    allowed: std::ops::RangeInclusive<u32>,
) -> Result<(), graph_core::file::PluginError> {
    match allowed.contains(&tile) {
        true => Ok(()),
        false => Err(graph_core::file::PluginError::Invalid(format!(
            "tile must be {} to {} pixels, got {tile}",
            allowed.start(),
            allowed.end()
        ))),
    }
}
