//! Keeping the shadow atlas while nothing it shows has moved: on such a frame
//! `shadow_raster` draws nothing and `shadow_resolve` copies the last frame's atlas (a
//! `History` of it) into this frame's. Shadow maps are the render graph's classic case of
//! work a frame can skip; the compute raster of `builtin:dense`'s nine shadowed lights
//! took 3.4 ms of a 6.9 ms frame on an H100 (docs/design/shadows.md).
//!
//! ```ron
//! "shadow_atlas_prev": History(of: "shadow_atlas", when: "shadows & !cpu_device"),
//! // in both passes:
//! inputs: { "previous": "shadow_atlas_prev" },  // the atlas as the last frame left it
//! params: (cache: Param(name: "shadow_cache", default: 1)),  // optional: 0 draws every frame
//! ```
//!
//! A frame keeps the atlas when its shadow work has the stamp of the work the kept atlas
//! was drawn from (gpu_scene/shadow_work.rs's `ShadowStamp`: the views as the GPU reads
//! them, the atlas's side, the options, and the count of frames that moved a caster), and
//! not after the history was reset (the first frame, a resize, a new plan,
//! `Executor::reset_history`) nor where a view draws an alpha MASK mesh (the hardware draws
//! those every frame). The two passes decide alike, each from the stamps it recorded
//! itself ([`gpu::Kept`](super::gpu::shadow_cache::Kept)), so they agree without a
//! resource between them; the raster takes `previous` only to learn of a reset. The
//! cascades follow the camera and each light's map size follows its share of the screen,
//! so a moved camera draws every map again: what is kept is a still frame's atlas.

use rgraph_core::file::{PluginError, Slots};
use rgraph_core::types::TextureFormat;
use rgraph_core::{PassBuilder, TextureHandle};

use crate::common::switch::Switch;
use crate::common::textures::{self, Want};

/// The `previous` input as the pass reads it: the last frame's atlas, where the file
/// gives the slot and `cache` is not off; `None` where the atlas is drawn every frame. An
/// error where `cache` is on without the slot, or the slot is not a history of an r32float
/// texture.
pub(crate) fn previous(
    cache: Option<Switch>,
    pass: &mut PassBuilder<'_>,
    slots: &mut Slots<'_>,
) -> Result<Option<TextureHandle>, PluginError> {
    if slots.kind("previous").is_none() {
        return match cache {
            Some(Switch::On) => Err(PluginError::Invalid(
                "keeping the shadow atlas (cache: true) needs a \"previous\" input: the atlas \
                 as the last frame left it, History(of: ..) of the atlas"
                    .into(),
            )),
            _ => Ok(None),
        };
    }
    let want = Want::new("the last frame's shadow atlas", &[TextureFormat::R32Float]).samples(1);
    let (previous, _) = textures::input(slots, pass, "previous", want)?;
    let previous = pass.sampled(previous);
    if pass.resource(previous).origin.history_of().is_none() {
        return Err(PluginError::Slot {
            slot: "previous".to_owned(),
            resource: slots.resource("previous").unwrap_or("previous").to_owned(),
            why: "is not a history, but a kept shadow atlas is the last frame's: \
                  History(of: ..) of the atlas"
                .to_owned(),
        });
    }
    Ok((cache != Some(Switch::Off)).then_some(previous))
}
