//! The `fullscreen` plugin; its contract is on [`Fullscreen`].

use serde::Deserialize;

use super::binding::BindingDecl;
use super::draw::{Blend, Draw};
use crate::builder::PassBuilder;
use crate::file::{Plugin, PluginError, Slots};
use crate::pass::PassKind;

/// `fullscreen`: a full-screen pass running a WGSL fragment shader from a file.
///
/// ```ron
/// (name: "tonemap", plugin: "fullscreen",
///  params: (
///      shader: "../shaders/tonemap.wgsl",   // relative to the graph file
///      entry: "fs_main",                    // the default
///      bindings: [Slot(binding: 0, slot: "hdr"), Sampler(binding: 1)],
///      blend: Replace,                      // Replace (default) | Additive | Alpha
///      clear: (0.0, 0.0, 0.0, 1.0),         // for outputs written fresh; default 0s
///  ),
///  inputs: { "hdr": "hdr" },
///  outputs: { "color": "ldr" })
/// ```
///
/// The vertex stage is built in (one full-screen triangle), so the shader needs only a
/// fragment entry point, which may take `@location(0) uv: vec2<f32>` ((0, 0) at the top
/// left) and builtins such as `@builtin(position)`. Output slots that no binding takes are
/// the color attachments, `@location(0)` upward in file order.
pub struct Fullscreen;

/// `fullscreen`'s parameters.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FullscreenParams {
    /// WGSL file, relative to the graph file.
    pub shader: String,
    /// The fragment entry point.
    #[serde(default = "fs_main")]
    pub entry: String,
    /// What the shader's bindings are bound to, checked against the shader when the file
    /// loads.
    #[serde(default)]
    pub bindings: Vec<BindingDecl>,
    /// How the output is combined with the target; `Replace` by default.
    #[serde(default)]
    pub blend: Blend,
    /// The clear color (linear RGBA) of color outputs written fresh (not modified);
    /// transparent black by default.
    #[serde(default)]
    pub clear: [f64; 4],
}

fn fs_main() -> String {
    "fs_main".into()
}

impl Plugin for Fullscreen {
    const NAME: &'static str = "fullscreen";
    type Params = FullscreenParams;

    fn kind(&self, _: &FullscreenParams) -> PassKind {
        PassKind::Render
    }

    fn setup(
        &self,
        params: FullscreenParams,
        pass: &mut PassBuilder<'_>,
        slots: &mut Slots<'_>,
    ) -> Result<(), PluginError> {
        Draw {
            shader: slots.shader(&params.shader)?,
            entry: &params.entry,
            bindings: &params.bindings,
            blend: params.blend,
            clear: params.clear,
        }
        .setup(pass, slots)
    }
}
