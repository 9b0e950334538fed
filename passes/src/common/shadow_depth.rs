//! What the two passes that draw the shadow maps' depth share (passes/shadow_maps.rs, the
//! hardware's; passes/shadow_raster.rs, the compute raster's small clusters): the
//! slope-scaled depth bias both apply alike, and the keys buffer the one writes and the
//! other reads, one word a texel of the square atlas.

use rgraph_core::file::PluginError;

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
