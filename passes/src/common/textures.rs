//! The textures in a deferred pass's slots: taking them through [`Slots`] and checking
//! their formats and sample counts, with errors naming the slot and the resource.

use rgraph_core::file::{PluginError, Slots};
use rgraph_core::types::TextureFormat;
use rgraph_core::{Aspect, ColorLoad, PassBuilder, Texture, TextureDesc, TextureHandle};

/// What a slot must hold.
#[derive(Copy, Clone, Debug)]
pub(crate) struct Want {
    /// What the texture is for, in messages: "the G-buffer's normals".
    pub what: &'static str,
    pub formats: &'static [TextureFormat],
    /// The sample count, when it must match another texture's.
    pub samples: Option<u32>,
}

use TextureFormat as F;
pub(crate) const ALBEDO: &[TextureFormat] = &[F::Rgba8Unorm, F::Rgba8UnormSrgb];
pub(crate) const NORMAL: &[TextureFormat] = &[F::Rg16Float];
pub(crate) const MATERIAL: &[TextureFormat] = &[F::Rgba8Unorm];
pub(crate) const VIEW_DEPTH: &[TextureFormat] = &[F::R32Float];
pub(crate) const HDR: &[TextureFormat] = &[F::Rgba16Float];
/// The lean G-buffer's emission, RGB9E5 (common.wgsl's `pack_rgb9e5`) low half in red:
/// WebGPU multisamples rg16uint, not r32uint.
pub(crate) const EMISSION: &[TextureFormat] = &[F::Rg16Uint];
/// A G-buffer's mesh index + 1 per sample (0 where no mesh drew), low half in red: two
/// halves, since WebGPU multisamples rg16uint everywhere and r32uint only on some devices.
pub(crate) const MESH: &[TextureFormat] = &[F::Rg16Uint];
/// A G-buffer's pose offset per sample (common/pose_offset.rs): where a deformed mesh's
/// point was in the last pose, from where it is, in world space; alpha unused (WebGPU
/// renders no three-channel half floats).
pub(crate) const POSE_OFFSET: &[TextureFormat] = &[F::Rgba16Float];
/// A visibility buffer's triangle IDs + 1: whole, or split low half in red where the
/// device does not multisample r32uint (geometry.wgsl's `SPLIT_IDS`).
pub(crate) const IDS: &[TextureFormat] = &[F::R32Uint, F::Rg16Uint];
pub(crate) const DEPTH_STENCIL: &[TextureFormat] =
    &[F::Depth24PlusStencil8, F::Depth32FloatStencil8];
/// The G-buffer's depth where no later pass needs stencil (the tiled compute path).
pub(crate) const DEPTH_ANY: &[TextureFormat] = &[
    F::Depth24PlusStencil8,
    F::Depth32FloatStencil8,
    F::Depth32Float,
];
/// Depth holding 32-bit floats exactly (a compute rasteriser's keys hold them).
pub(crate) const DEPTH_FLOAT: &[TextureFormat] = &[F::Depth32Float, F::Depth32FloatStencil8];
pub(crate) const DISPLAY: &[TextureFormat] = &[F::Rgba8UnormSrgb, F::Rgba8Unorm];
pub(crate) const EXPOSURE: &[TextureFormat] = &[F::R32Float];

/// The G-buffer textures the light passes, the edge pass and the G-buffer resolve read, by
/// slot and group-1 binding (gbuffer_read.wgsl).
pub(crate) const GBUFFER_INPUTS: [(&str, &str, &[TextureFormat], u32); 4] = [
    ("albedo", "the G-buffer's albedo", ALBEDO, 0),
    ("normal", "the G-buffer's normals", NORMAL, 1),
    ("material", "the G-buffer's material", MATERIAL, 2),
    ("view_depth", "the G-buffer's view depth", VIEW_DEPTH, 3),
];

impl Want {
    pub const fn new(what: &'static str, formats: &'static [TextureFormat]) -> Want {
        Want {
            what,
            formats,
            samples: None,
        }
    }

    pub const fn samples(self, samples: u32) -> Want {
        Want {
            samples: Some(samples),
            ..self
        }
    }
}

/// The handle of input-only `slot`, checked against `want`.
pub(crate) fn input(
    slots: &mut Slots<'_>,
    pass: &PassBuilder<'_>,
    slot: &str,
    want: Want,
) -> Result<(TextureHandle, TextureDesc), PluginError> {
    let handle = slots.input::<Texture>(slot)?;
    let desc = check(slots, pass, slot, handle, want)?;
    Ok((handle, desc))
}

/// Writes output `slot` through `declare` (given the handle and whether the file has the
/// slot in `inputs` too), then checks it against `want`.
pub(crate) fn output(
    slots: &mut Slots<'_>,
    pass: &mut PassBuilder<'_>,
    slot: &str,
    want: Want,
    declare: impl FnOnce(&mut PassBuilder<'_>, TextureHandle, bool) -> TextureHandle,
) -> Result<(TextureHandle, TextureDesc), PluginError> {
    let handle = slots.write::<Texture>(slot, |t| declare(pass, t.handle, t.modifies))?;
    let desc = check(slots, pass, slot, handle, want)?;
    Ok((handle, desc))
}

/// A color attachment written fresh (cleared to `clear`), or drawn over when the file
/// has the slot in `inputs` too.
pub(crate) fn color_output(
    slots: &mut Slots<'_>,
    pass: &mut PassBuilder<'_>,
    slot: &str,
    want: Want,
    clear: [f64; 4],
) -> Result<(TextureHandle, TextureDesc), PluginError> {
    attached_output(slots, pass, slot, want, ColorLoad::Clear(clear))
}

/// [`color_output`] for a pass that draws every pixel of its target (a full-screen
/// triangle, nothing discarded): begun without a clear, which on a chip with few ROPs
/// costs as much as the pass's own writes (docs/design/compute-raster.md, run visibility-merged).
pub(crate) fn covered_output(
    slots: &mut Slots<'_>,
    pass: &mut PassBuilder<'_>,
    slot: &str,
    want: Want,
) -> Result<(TextureHandle, TextureDesc), PluginError> {
    attached_output(slots, pass, slot, want, ColorLoad::Overwrite)
}

/// The next color attachment, beginning as `fresh` says where the pass writes a new
/// version, loaded where it adds to its input.
pub(crate) fn attached_output(
    slots: &mut Slots<'_>,
    pass: &mut PassBuilder<'_>,
    slot: &str,
    want: Want,
    fresh: ColorLoad,
) -> Result<(TextureHandle, TextureDesc), PluginError> {
    output(slots, pass, slot, want, |pass, handle, modifies| {
        let load = if modifies { ColorLoad::Load } else { fresh };
        pass.color_output(handle, load)
    })
}

/// An output slot the pass adds to (`hdr` of the light passes, `depth` of the edge pass):
/// the file must list it in `inputs` as well.
pub(crate) fn must_modify(
    slots: &Slots<'_>,
    slot: &str,
    modifies: bool,
    why: &str,
) -> Result<(), PluginError> {
    if modifies {
        return Ok(());
    }
    Err(PluginError::Slot {
        slot: slot.to_owned(),
        resource: slots.resource(slot).unwrap_or(slot).to_owned(),
        why: format!("is only in outputs, but the pass {why}: list the slot in inputs too"),
    })
}

fn check(
    slots: &Slots<'_>,
    pass: &PassBuilder<'_>,
    slot: &str,
    handle: TextureHandle,
    want: Want,
) -> Result<TextureDesc, PluginError> {
    let error = |why: String| PluginError::Slot {
        slot: slot.to_owned(),
        resource: slots.resource(slot).unwrap_or(slot).to_owned(),
        why,
    };
    let Some(desc) = pass.resource(handle).texture().cloned() else {
        return Err(error("is not a texture".to_owned()));
    };
    // A fallback format must fit as well (the device decides which one the pass gets),
    // and a conditional one that may be chosen where the pass runs.
    let formats = desc.formats_where(pass.condition());
    if let Some(format) = formats.into_iter().find(|f| !want.formats.contains(f)) {
        let expected: Vec<String> = want.formats.iter().map(|f| format_name(*f)).collect();
        return Err(error(format!(
            "is {}, but {} must be {}",
            format_name(format),
            want.what,
            expected.join(" or ")
        )));
    }
    match want.samples {
        Some(samples) if samples != desc.samples => Err(error(format!(
            "has {} sample(s), but {} must have {samples}",
            desc.samples, want.what
        ))),
        _ => Ok(desc),
    }
}

/// A format as graph files spell it: `rgba16float`.
pub(crate) fn format_name(format: TextureFormat) -> String {
    ron::to_string(&format)
        .map(|s| s.trim_matches('"').to_owned())
        .unwrap_or_else(|_| format!("{format:?}"))
}

/// A texture a pass's shader binds (group 1), as the plugin declared it.
#[derive(Copy, Clone, Debug)]
#[cfg_attr(not(feature = "gpu"), allow(dead_code))]
pub(crate) struct Input {
    pub binding: u32,
    pub texture: TextureHandle,
    pub aspect: Aspect,
    pub texels: Texels,
}

/// What a shader reads from an input texture.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
#[cfg_attr(not(feature = "gpu"), allow(dead_code))]
pub(crate) enum Texels {
    /// `f32` color (`GTexF`), never filtered.
    Float,
    /// `f32` color of a single-sampled filterable format, sampled bilinearly through a
    /// clamp-to-edge linear sampler bound at `sampler` (post filters such as FXAA, whose
    /// taps between texels rely on the filtering hardware).
    Filtered { sampler: u32 },
    /// `f32` of a single-sampled format, filterable or not, read four texels at a time by
    /// `textureGather` through a clamp-to-edge nearest sampler bound at `sampler` (the
    /// shadow atlas's percentage-closer filter, which compares each texel itself).
    Gathered { sampler: u32 },
    /// `u32` (`GTexU`): the stencil aspect.
    Uint,
    /// The depth aspect (`GTexD`).
    Depth,
    /// Written as a write-only storage texture of its planned format (compute passes).
    Store,
}

impl Input {
    /// A color texture at `binding`.
    pub fn color(binding: u32, texture: TextureHandle) -> Input {
        Input {
            binding,
            texture,
            aspect: Aspect::All,
            texels: Texels::Float,
        }
    }
}

/// Declares `slot` sampled and returns it as the input at `binding`.
pub(crate) fn sampled(
    slots: &mut Slots<'_>,
    pass: &mut PassBuilder<'_>,
    slot: &str,
    want: Want,
    binding: u32,
) -> Result<(Input, TextureDesc), PluginError> {
    let (handle, desc) = input(slots, pass, slot, want)?;
    pass.sampled(handle);
    Ok((Input::color(binding, handle), desc))
}
