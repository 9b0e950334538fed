//! The `clear` plugin; its contract is on [`Clear`].

use serde::Deserialize;

use crate::access::{AspectAccess, ColorLoad};
use crate::builder::PassBuilder;
use crate::file::{Plugin, PluginError, Slots};
use crate::handle::{Texture, TextureHandle};
use crate::pass::PassKind;

/// `clear`: clears output slot `target` (color, or depth and stencil for depth-stencil
/// formats) and draws nothing.
///
/// ```ron
/// (name: "clear", plugin: "clear",
///  params: (color: (0.0, 0.0, 0.0, 1.0), depth: 1.0, stencil: 0),   // these defaults
///  outputs: { "target": "hdr" })
/// ```
///
/// The color must be finite and the depth within `0.0 ..= 1.0`.
pub struct Clear;

/// `clear`'s parameters. Only the aspects the target's format has are used.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ClearParams {
    /// RGBA for a color target, linear, 0 to 1 for unorm formats; opaque black by default.
    #[serde(default = "opaque_black")]
    pub color: [f64; 4],
    /// Depth for a depth target, within `0.0 ..= 1.0`; 1.0 (the far plane of a
    /// conventional depth buffer) by default.
    #[serde(default = "far")]
    pub depth: f32,
    /// Stencil value for a target with a stencil aspect; 0 by default.
    #[serde(default)]
    pub stencil: u32,
}

fn opaque_black() -> [f64; 4] {
    [0.0, 0.0, 0.0, 1.0]
}

fn far() -> f32 {
    1.0
}

impl Plugin for Clear {
    const NAME: &'static str = "clear";
    type Params = ClearParams;

    fn kind(&self, _: &ClearParams) -> PassKind {
        PassKind::Render
    }

    fn setup(
        &self,
        params: ClearParams,
        pass: &mut PassBuilder<'_>,
        slots: &mut Slots<'_>,
    ) -> Result<(), PluginError> {
        // A NaN or infinite clear reaches the device as is and leaves the target undefined
        // (black on most drivers): refused here, where the file can be named.
        if !params.color.iter().all(|c| c.is_finite()) {
            return Err(PluginError::Invalid(format!(
                "clear color {:?} is not finite",
                params.color
            )));
        }
        if !(0.0..=1.0).contains(&params.depth) {
            return Err(PluginError::Invalid(format!(
                "clear depth {} is not within 0.0 ..= 1.0",
                params.depth
            )));
        }
        slots.write::<Texture>("target", |t| declare(pass, t.handle, &params))?;
        Ok(())
    }
}

fn declare(
    pass: &mut PassBuilder<'_>,
    target: TextureHandle,
    params: &ClearParams,
) -> TextureHandle {
    match pass.resource(target).texture().map(|d| d.format) {
        Some(format) if format.is_depth_stencil_format() => {
            // An aspect the format lacks is declared read-only, which the builder records
            // as absent.
            let depth = match format.has_depth_aspect() {
                true => AspectAccess::Clear(params.depth),
                false => AspectAccess::ReadOnly,
            };
            let stencil = match format.has_stencil_aspect() {
                true => AspectAccess::Clear(params.stencil),
                false => AspectAccess::ReadOnly,
            };
            pass.depth_stencil(target, depth, stencil)
        }
        _ => pass.color_output(target, ColorLoad::Clear(params.color)),
    }
}
