//! What every deferred plugin of one registry shares ([`Shared`]), through which a pass
//! set up in `Plugin::setup` gets its record callback.

use std::sync::Arc;

use rgraph_core::file::PluginError;
use rgraph_core::PassBuilder;

use super::optional_targets::{OptionalTargets, PerKept};
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

    /// Gives the pass `recorder`'s record callback. Without feature `gpu` graphs are only
    /// declared and validated, and what a pass would record is dropped.
    #[cfg(feature = "gpu")]
    pub fn record(&self, pass: &mut PassBuilder<'_>, recorder: impl crate::common::gpu::Recorder) {
        crate::common::gpu::recorder::declare(pass, recorder, self.scenes.clone());
    }

    #[cfg(not(feature = "gpu"))]
    pub fn record<R>(&self, _: &mut PassBuilder<'_>, _: R) {}

    /// Gives the pass the callback of `make`'s recorder for the optional `targets` its
    /// file gives it (material layers, a pose offset): made once where the file gives
    /// none, else per set of them a frame's plan keeps ([`PerKept`], which checks `make`
    /// for all of them now).
    pub fn record_kept<T: OptionalTargets, R: Recordable>(
        &self,
        pass: &mut PassBuilder<'_>,
        targets: T,
        make: impl Fn(T::Set) -> Result<R, PluginError> + 'static,
    ) -> Result<(), PluginError> {
        if targets.is_empty() {
            self.record(pass, make(targets.all())?);
        } else {
            self.record(pass, PerKept::new(targets, Box::new(make))?);
        }
        Ok(())
    }
}

/// What [`Shared::record`] takes, [`PerKept`] around it included: a recorder of the
/// scene (feature `gpu`), else anything.
#[cfg(feature = "gpu")]
pub(crate) trait Recordable: crate::common::gpu::Recorder<Scene: Clone> {}
#[cfg(feature = "gpu")]
impl<R: crate::common::gpu::Recorder<Scene: Clone>> Recordable for R {}
#[cfg(not(feature = "gpu"))]
pub(crate) trait Recordable: 'static {}
#[cfg(not(feature = "gpu"))]
impl<R: 'static> Recordable for R {}

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
) -> Result<(), rgraph_core::file::PluginError> {
    match allowed.contains(&tile) {
        true => Ok(()),
        false => Err(rgraph_core::file::PluginError::Invalid(format!(
            "tile must be {} to {} pixels, got {tile}",
            allowed.start(),
            allowed.end()
        ))),
    }
}
