//! The `copy` plugin; its contract is on [`Copy`](struct@Copy).

use serde::Deserialize;

use super::binding::texture_desc;
use crate::access::BufferRole;
use crate::builder::PassBuilder;
use crate::file::{Plugin, PluginError, Slots};
use crate::handle::{Buffer, Kind, Texture};
use crate::pass::PassKind;
use crate::resource::format_name;

/// `copy`: copies input slot `src` into output slot `dst`, both textures (same size,
/// layer count and copy-compatible format, single-sampled; mip 0 of every layer is
/// copied) or both buffers (`dst` at least as large; all of `src` is copied).
///
/// ```ron
/// (name: "history", plugin: "copy", inputs: { "src": "hdr" }, outputs: { "dst": "prev" })
/// ```
pub struct Copy;

/// `copy`'s parameters: none.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CopyParams {}

impl Plugin for Copy {
    const NAME: &'static str = "copy";
    type Params = CopyParams;

    fn kind(&self, _: &CopyParams) -> PassKind {
        PassKind::Transfer
    }

    fn setup(
        &self,
        _: CopyParams,
        pass: &mut PassBuilder<'_>,
        slots: &mut Slots<'_>,
    ) -> Result<(), PluginError> {
        match slots.kind("src") {
            Some(Kind::Buffer) => copy_buffer(pass, slots),
            _ => copy_texture(pass, slots),
        }
    }
}

fn copy_texture(pass: &mut PassBuilder<'_>, slots: &mut Slots<'_>) -> Result<(), PluginError> {
    let src = slots.input::<Texture>("src")?;
    pass.copy_src(src);
    let dst = slots.write::<Texture>("dst", |t| pass.copy_dst(t.handle))?;
    let (from, to) = (texture_desc(pass, src)?, texture_desc(pass, dst)?);
    if from.samples > 1 || to.samples > 1 {
        return Err(misfit(
            slots,
            "multisampled textures cannot be copied (resolve them instead)".into(),
        ));
    }
    if from.format.remove_srgb_suffix() != to.format.remove_srgb_suffix() {
        return Err(misfit(
            slots,
            format!(
                "is {}, which cannot be copied from {}",
                format_name(to.format),
                format_name(from.format)
            ),
        ));
    }
    if (from.size, from.layers) != (to.size, to.layers) {
        return Err(misfit(
            slots,
            format!(
                "is {:?} with {} layer(s), but the source is {:?} with {}",
                to.size, to.layers, from.size, from.layers
            ),
        ));
    }
    #[cfg(feature = "gpu")]
    pass.transfer(move |ctx| {
        let shape = ctx.resources.shape(src);
        let info = |texture| wgpu::TexelCopyTextureInfo {
            texture,
            mip_level: 0,
            origin: wgpu::Origin3d::ZERO,
            aspect: wgpu::TextureAspect::All,
        };
        ctx.encoder.copy_texture_to_texture(
            info(ctx.resources.texture(src)),
            info(ctx.resources.texture(dst)),
            wgpu::Extent3d {
                width: shape.width,
                height: shape.height,
                depth_or_array_layers: shape.layers,
            },
        );
    });
    Ok(())
}

fn copy_buffer(pass: &mut PassBuilder<'_>, slots: &mut Slots<'_>) -> Result<(), PluginError> {
    let src = slots.input::<Buffer>("src")?;
    pass.buffer(src, BufferRole::CopySrc);
    let dst = slots.write::<Buffer>("dst", |t| pass.buffer(t.handle, BufferRole::CopyDst))?;
    // The byte count is fixed when the pass is set up, before an output size exists.
    for (slot, handle) in [("src", src), ("dst", dst)] {
        if pass
            .resource(handle)
            .buffer()
            .is_some_and(|b| b.per_sample != 0)
        {
            return Err(PluginError::Slot {
                slot: slot.into(),
                resource: slots.resource(slot).unwrap_or(slot).to_owned(),
                why:
                    "is sized per sample of the output; copy_buffer copies buffers of a fixed size"
                        .into(),
            });
        }
    }
    let size = |h| pass.resource(h).buffer().map_or(0, |b| b.size);
    let (from, to) = (size(src), size(dst));
    if from % wgpu_types::COPY_BUFFER_ALIGNMENT != 0 {
        return Err(PluginError::Slot {
            slot: "src".into(),
            resource: slots.resource("src").unwrap_or("src").to_owned(),
            why: format!("has {from} bytes, which is not a multiple of 4 as copies need"),
        });
    }
    if to < from {
        return Err(misfit(
            slots,
            format!("has {to} bytes, fewer than the {from} copied into it"),
        ));
    }
    #[cfg(feature = "gpu")]
    pass.transfer(move |ctx| {
        let (src, dst) = (ctx.resources.buffer(src), ctx.resources.buffer(dst));
        ctx.encoder.copy_buffer_to_buffer(src, 0, dst, 0, from);
    });
    Ok(())
}

/// `dst` does not fit what is copied into it.
fn misfit(slots: &Slots<'_>, why: String) -> PluginError {
    PluginError::Slot {
        slot: "dst".into(),
        resource: slots.resource("dst").unwrap_or("dst").to_owned(),
        why,
    }
}
