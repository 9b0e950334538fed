//! Material factors checked against what glTF allows: a value that is not a finite f32
//! (`1e39` in the file arrives as infinity, which would shade pixels with infinities and NaN)
//! is an error; a finite value outside glTF's range is clamped into it, with a warning.

use std::ops::RangeInclusive;
use std::path::Path;

use crate::SceneError;

/// Checks one factor (its components `values`) of material `material`: `field` names it in
/// messages.
pub(super) fn checked(
    file: &Path,
    material: &str,
    field: &str,
    values: &[f32],
    range: RangeInclusive<f32>,
    warnings: &mut Vec<String>,
) -> Result<Vec<f32>, SceneError> {
    if values.iter().any(|v| !v.is_finite()) {
        return Err(SceneError::InvalidMaterial {
            file: file.to_owned(),
            material: material.to_owned(),
            reason: format!(
                "{field} {values:?} is beyond the largest f32 ({:e})",
                f32::MAX
            ),
        });
    }
    let clamped: Vec<f32> = values
        .iter()
        .map(|v| v.clamp(*range.start(), *range.end()))
        .collect();
    if clamped != values {
        let allowed = match *range.end() == f32::MAX {
            true => format!("at least {}", range.start()),
            false => format!("within {}..={}", range.start(), range.end()),
        };
        warnings.push(format!(
            "{material}: {field} {values:?} is not {allowed}; clamped to {clamped:?}"
        ));
    }
    Ok(clamped)
}
