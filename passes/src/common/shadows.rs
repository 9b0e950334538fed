//! The light passes' optional `shadows` input: the shadow atlas, the depth the
//! `shadow_maps` pass draws (passes/shadow_maps.rs) or the r32float `shadow_resolve`
//! writes from the compute raster's keys on a GPU (passes/shadow_resolve.rs), through
//! which each shadowed light's direct light is scaled by the share of its shadow-map
//! filter's taps that see the surface (shadow.wgsl). Without the slot the generated WGSL is shadow_none.wgsl: every light
//! reaches every surface, and the image is the unshadowed pass's, bit for bit.

use rgraph_core::file::{PluginError, Slots};
use rgraph_core::types::TextureFormat;
use rgraph_core::{Aspect, PassBuilder, TextureHandle};

use super::textures::{self, Input, Texels, Want};
use crate::shaders;
use crate::shadows::ShadowFilter;

/// The shadow atlas's formats: depth the hardware raster writes, or 32-bit floats a
/// compute pass writes (no depth format is a storage texture). Both bind as unfilterable
/// `f32` textures, so one shader reads either: shadow.wgsl loads texels and filters them
/// itself.
pub(crate) const ATLAS: &[TextureFormat] = &[TextureFormat::Depth32Float, TextureFormat::R32Float];

/// Where the passes bind it: group 1 of the light passes, after every other input of
/// theirs (light_tiled's list of edge pixels is 12); group 2 of a pass that draws the
/// meshes (forward), whose group 1 is the material's. Its nearest sampler, for
/// `textureGather`, follows it.
const BINDING: u32 = 13;
const SAMPLER: u32 = 14;

/// The `shadows` slot when the file gives one: declared sampled (one sample), bound at
/// [`BINDING`] and gathered through a nearest sampler at [`SAMPLER`].
pub(crate) fn input(
    slots: &mut Slots<'_>,
    pass: &mut PassBuilder<'_>,
) -> Result<Option<Input>, PluginError> {
    if slots.kind("shadows").is_none() {
        return Ok(None);
    }
    let want = Want::new("the shadow atlas", ATLAS).samples(1);
    let (atlas, _) = textures::input(slots, pass, "shadows", want)?;
    pass.sampled(atlas);
    Ok(Some(Input {
        binding: BINDING,
        texture: atlas,
        aspect: Aspect::All,
        texels: Texels::Gathered { sampler: SAMPLER },
    }))
}

/// The WGSL for [`input`]'s result bound in `group`, composed after the light shader:
/// lighting.wgsl's `light_visibility`, from the atlas filtered as `filter` says, or 1
/// without an atlas.
pub(crate) fn wgsl(input: Option<&Input>, group: u32, filter: ShadowFilter) -> String {
    match input {
        Some(input) => format!(
            "// Generated: the shadows input (common/shadows.rs).\n\
             @group({group}) @binding({}) var shadow_atlas: texture_2d<f32>;\n\
             @group({group}) @binding({SAMPLER}) var shadow_texels: sampler;\n\
             const SHADOW_FILTER: u32 = {}u;\n{}",
            input.binding,
            filter.constant(),
            shaders::SHADOW
        ),
        None => shaders::SHADOW_NONE.to_owned(),
    }
}

/// A pass's recorder as its shadows input makes it: the pass with the atlas (or without,
/// where it has none), and, where the file marks the slot optional, the pass without it
/// too, which the recording picks where the plan drops the read
/// (`FrameResources::has`, common/gpu/shadowed.rs).
#[cfg_attr(not(feature = "gpu"), allow(dead_code))]
pub(crate) struct Shadowed<R> {
    pub with: R,
    /// The atlas the plan may drop, and the pass without it.
    pub without: Option<(TextureHandle, R)>,
}

/// `make`'s pass for [`input`]'s atlas, and where the slot is `optional` ([`optional`]),
/// for none too.
pub(crate) fn variants<R>(
    optional: bool,
    input: Option<Input>,
    mut make: impl FnMut(Option<&Input>) -> Result<R, PluginError>,
) -> Result<Shadowed<R>, PluginError> {
    let with = make(input.as_ref())?;
    let without = match input {
        Some(atlas) if optional => Some((atlas.texture, make(None)?)),
        _ => None,
    };
    Ok(Shadowed { with, without })
}

/// Whether the file marks the `shadows` slot optional: the plan may drop the atlas.
pub(crate) fn optional(slots: &Slots<'_>) -> bool {
    slots.optional("shadows")
}
