//! A visibility buffer rasterised in compute, as a graph buffer: each sample's 64-bit key,
//! the bits of its reversed-Z depth (a positive float, so its bits order as its values)
//! over the ID + 1 of the triangle it shows, 0 where nothing was drawn (the far depth), in
//! a plane per sample; sample 0's key also says whether the pixel's samples show more than
//! one triangle, so that a reader loads the other planes only there (key_layout.wgsl).
//! `visibility_compute` writes it, `light_tiled` and `keys_depth` read it
//! (visibility_samples.wgsl). A file declares it `Buffer(per_sample: 8, samples: 4)` for 4
//! samples per pixel: 8 bytes each, as a hardware visibility buffer's depth32float and
//! r32uint take.

use rgraph_core::file::{PluginError, Slots};
use rgraph_core::{Buffer, BufferHandle, BufferRole, PassBuilder};

/// Bytes of one sample's key.
pub(crate) const KEY_BYTES: u64 = 8;

/// Where visibility_samples.wgsl reads the keys: group 1, this binding.
#[cfg_attr(not(feature = "gpu"), allow(dead_code))]
pub(crate) const KEYS_BINDING: u32 = 8;

/// The sample counts the passes know the positions of (shaders.rs).
const SAMPLE_COUNTS: [u32; 4] = [1, 2, 4, 8];

/// The samples per pixel of the buffer in `slot`, which must hold 8 bytes per sample
/// (1, 2, 4 or 8 of them) and nothing else.
pub(crate) fn sample_count(
    pass: &PassBuilder<'_>,
    slots: &Slots<'_>,
    slot: &str,
    handle: BufferHandle,
) -> Result<u32, PluginError> {
    let resource = || slots.resource(slot).unwrap_or(slot).to_owned();
    let Some(desc) = pass.resource(handle).buffer().copied() else {
        return Err(PluginError::Slot {
            slot: slot.to_owned(),
            resource: resource(),
            why: "is not a buffer".into(),
        });
    };
    let fits =
        desc.size == 0 && desc.per_sample == KEY_BYTES && SAMPLE_COUNTS.contains(&desc.samples);
    if !fits {
        return Err(PluginError::Slot {
            slot: slot.to_owned(),
            resource: resource(),
            why: format!(
                "holds {} bytes per sample, {} samples per pixel and {} bytes more: a \
                 visibility buffer in compute holds {KEY_BYTES} bytes per sample and nothing \
                 else (Buffer(per_sample: {KEY_BYTES}, samples: 1, 2, 4 or 8))",
                desc.per_sample, desc.samples, desc.size
            ),
        });
    }
    Ok(desc.samples)
}

/// Takes input `slot` as a visibility buffer the pass reads (as read-only storage):
/// its handle and samples per pixel, checked as [`sample_count`] checks them.
pub(crate) fn read(
    pass: &mut PassBuilder<'_>,
    slots: &mut Slots<'_>,
    slot: &str,
) -> Result<(BufferHandle, u32), PluginError> {
    let keys = slots.input::<Buffer>(slot)?;
    let read = BufferRole::Storage {
        read: true,
        write: false,
    };
    pass.buffer(keys, read);
    Ok((keys, sample_count(pass, slots, slot, keys)?))
}

/// Whether the device can bind `buffer`, a visibility buffer, as one storage binding; the
/// reason if not (the output too large for it at its sample count).
#[cfg(feature = "gpu")]
pub(crate) fn fits_binding(device: &wgpu::Device, buffer: &wgpu::Buffer) -> Result<(), String> {
    let limit = device.limits().max_storage_buffer_binding_size;
    match buffer.size() <= limit {
        true => Ok(()),
        false => Err(format!(
            "the visibility buffer's {} bytes ({KEY_BYTES} per sample) exceed this device's \
             storage binding limit of {limit} bytes: render smaller or with fewer samples, or \
             with deferred_msaa_4x_lean.ron, whose G-buffer is textures",
            buffer.size()
        )),
    }
}
