//! A full-screen draw of a deferred shader, as the edge, resolve, tone-mapping, debug and
//! transparent-composite plugins set it up; `gpu::fullscreen` records it.

use graph_core::types::BlendState;
use graph_core::TextureHandle;

use super::textures::Input;
use super::Recording;

#[cfg_attr(not(feature = "gpu"), allow(dead_code))]
pub(crate) struct Fullscreen {
    pub label: &'static str,
    /// The composed WGSL; its vertex entry point is `vs_fullscreen` (common.wgsl).
    pub source: String,
    pub entry: &'static str,
    pub constants: Vec<(&'static str, f64)>,
    /// Group 1.
    pub inputs: Vec<Input>,
    /// The shader reads the scene (group 0); without a host such a pass draws nothing.
    pub reads_scene: bool,
    /// The color attachment, if any.
    pub target: Option<TextureHandle>,
    /// A depth-stencil attachment whose stencil the pass marks: `Replace` with the
    /// reference 0x80 through write mask 0x80, wherever the shader does not discard.
    pub stencil_mark: Option<TextureHandle>,
    /// How the shader's output combines with the color attachment; `None` replaces it.
    pub blend: Option<BlendState>,
}

impl Recording for Fullscreen {
    #[cfg(feature = "gpu")]
    fn record(self, scenes: std::sync::Arc<crate::gpu_scene::SceneCache>) -> graph_core::Record {
        graph_core::Record::Render(crate::gpu::fullscreen::record(self, scenes))
    }
}
