//! What the passes that make the shadow atlas share (passes/shadow_maps.rs, the
//! hardware's raster; passes/shadow_raster.rs, the compute raster; passes/shadow_resolve.rs,
//! the atlas from its keys): the slope-scaled depth bias both rasters apply alike, the
//! atlas's shape, and the keys buffer, one word a texel of the square atlas.

use rgraph_core::file::{PluginError, Slots};
use rgraph_core::{Buffer, BufferHandle, BufferRole, PassBuilder, Size};

use crate::shadows::ATLAS_UNITS;

/// The default slope-scaled depth bias: depth pushed away from the light by this times
/// the larger of a triangle's depth changes per texel across and down.
pub(crate) fn slope_bias() -> f32 {
    2.0
}

/// `bias` as a pass's `slope_bias` parameter, checked: finite and 0 or more.
pub(crate) fn check_slope_bias(bias: f32) -> Result<(), PluginError> {
    match bias.is_finite() && bias >= 0.0 {
        true => Ok(()),
        false => Err(PluginError::Invalid(format!(
            "slope_bias must be finite and 0 or more, got {bias}"
        ))),
    }
}

/// Checks that output `slot`'s texture, of `size`, is an atlas: square, its side a
/// multiple of [`ATLAS_UNITS`].
pub(crate) fn check_atlas(slots: &Slots<'_>, slot: &str, size: Size) -> Result<(), PluginError> {
    match size {
        Size::Absolute(w, h) if w == h && w >= ATLAS_UNITS && w % ATLAS_UNITS == 0 => Ok(()),
        _ => Err(PluginError::Slot {
            slot: slot.to_owned(),
            resource: slots.resource(slot).unwrap_or(slot).to_owned(),
            why: format!(
                "is {size:?}, but the shadow atlas must be Absolute(N, N), N a multiple of \
                 {ATLAS_UNITS} (maps are placed on a grid of {ATLAS_UNITS} x {ATLAS_UNITS} \
                 units)"
            ),
        }),
    }
}

/// Takes the `keys` input (read-only storage), checked to hold 4 bytes a texel of the
/// atlas of `size`.
pub(crate) fn keys(
    pass: &mut PassBuilder<'_>,
    slots: &mut Slots<'_>,
    size: Size,
) -> Result<BufferHandle, PluginError> {
    let keys = slots.input::<Buffer>("keys")?;
    let read = BufferRole::Storage {
        read: true,
        write: false,
    };
    pass.buffer(keys, read);
    // A slot that takes a buffer holds one: its description is there.
    let bytes = pass.resource(keys).buffer().map_or(0, |d| d.size);
    let atlas = match size {
        Size::Absolute(w, _) => Some(w),
        _ => None,
    };
    if atlas_of_keys(bytes) != atlas || atlas.is_none() {
        return Err(PluginError::Slot {
            slot: "keys".to_owned(),
            resource: slots.resource("keys").unwrap_or("keys").to_owned(),
            why: format!(
                "holds {bytes} bytes, but the keys of a {size:?} atlas take 4 bytes a \
                 texel: Buffer(per_texel: 4, texels: (N, N)) for Absolute(N, N)"
            ),
        });
    }
    Ok(keys)
}

/// The side of the atlas whose keys fill `bytes`: 4 bytes a texel, a square.
pub(crate) fn atlas_of_keys(bytes: u64) -> Option<u32> {
    let texels = bytes / 4;
    let side = (texels as f64).sqrt().round() as u64;
    (side * side == texels && bytes.is_multiple_of(4) && side > 0)
        .then(|| u32::try_from(side).ok())
        .flatten()
}

#[cfg(test)]
mod tests {
    use super::{atlas_of_keys, check_slope_bias};

    #[test]
    fn keys_of_a_square_atlas_give_its_side() {
        assert_eq!(atlas_of_keys(4 * 4096 * 4096), Some(4096));
        assert_eq!(atlas_of_keys(4 * 4096 * 2048), None);
        assert_eq!(atlas_of_keys(6), None);
        assert_eq!(atlas_of_keys(0), None);
    }

    #[test]
    fn a_slope_bias_is_finite_and_not_negative() {
        assert!(check_slope_bias(0.0).is_ok() && check_slope_bias(2.0).is_ok());
        assert!(check_slope_bias(-1.0).is_err() && check_slope_bias(f32::NAN).is_err());
    }
}
