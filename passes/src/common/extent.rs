//! Where a pass draws: every pixel, or only those the scene's blended meshes may cover,
//! for the passes that serve the transparent pass alone (`keys_depth`'s depth, the
//! transparent accumulation's start). On a chip with few ROPs a multisampled full-screen
//! write costs as much as a full-screen pass (docs/design/compute-raster.md, run visibility-merged),
//! and blended meshes often cover a small part of the output.

use serde::Deserialize;

/// Which pixels a pass draws (`extent` in a graph file: `full`, the default, or
/// `blended`).
#[derive(Clone, Copy, Debug, Default, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum Extent {
    /// Every pixel.
    #[default]
    Full,
    /// Those the scene's blended meshes may cover (the bounds of their world boxes on
    /// screen, [`GpuScene::blended_rect`]); elsewhere whatever the texture held, which no
    /// blended fragment lies over to read.
    ///
    /// [`GpuScene::blended_rect`]: crate::gpu_scene::GpuScene::blended_rect
    Blended,
}

#[cfg(feature = "gpu")]
impl Extent {
    /// The pixels of a target of `size` drawn for `scene`: `None` for none (nothing
    /// blended in view).
    pub(crate) fn rect(
        self,
        scene: &crate::gpu_scene::GpuScene,
        size: (u32, u32),
    ) -> Option<crate::gpu_scene::screen_rect::PixelRect> {
        match self {
            Extent::Full => Some(crate::gpu_scene::screen_rect::PixelRect::full(size)),
            Extent::Blended => scene.blended_rect(size),
        }
    }
}
