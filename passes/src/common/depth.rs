//! The depth convention a pass uses: what its `reversed_z` parameter says, or, without
//! one, what suits the depth format the compile picked.
//!
//! Reversed-Z (near at 1, far at 0) pays off only in a float depth format: float
//! precision is densest near 0, which is where perspective squeezes distant geometry, so
//! the two even out. A unorm format steps uniformly, and reversing it changes nothing
//! but the compares; standard Z keeps those the familiar way round. Hence the rule
//! without a parameter: reversed-Z for `depth32float` and `depth32float-stencil8`,
//! standard Z for `depth16unorm` and `depth24plus*`. The depth format is the pipeline's
//! to choose (a fallback, or a conditional one under `shallow_depth`), so every pass
//! that touches one depth buffer follows the same format and agrees without being told.
//! An explicit `reversed_z: true` or `false` is honoured whatever the format; then the
//! passes sharing a depth buffer must say the same.

use rgraph_core::types::TextureFormat;
use rgraph_core::{AspectAccess, ByFormat, PassBuilder, TextureHandle};

use rgraph_scene::DepthConvention;

/// A pass's depth convention, from its optional `reversed_z` parameter; resolved
/// against the depth format when the format is known (at record time, or, for the
/// clear value, when the graph compiles).
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(crate) struct DepthRule {
    reversed_z: Option<bool>,
}

impl DepthRule {
    pub fn new(reversed_z: Option<bool>) -> DepthRule {
        DepthRule { reversed_z }
    }

    /// The convention for a depth buffer of `format`.
    #[cfg_attr(not(feature = "gpu"), allow(dead_code))]
    pub fn convention(self, format: TextureFormat) -> DepthConvention {
        self.reversed_z
            .map_or_else(|| format_convention(format), named)
    }

    /// Binds `depth` as the attachment of a pass that starts the depth buffer: depth
    /// cleared as [`clear`](Self::clear) says, stencil to 0 where the format has one
    /// (depth32float has none: the lean G-buffer and the visibility buffer, read by the
    /// tiled pass, need no stencil). Returns the written version.
    pub fn start(self, pass: &mut PassBuilder<'_>, depth: TextureHandle) -> TextureHandle {
        let stencil = stencil_where_present(pass, depth, AspectAccess::Clear(0));
        pass.depth_stencil(depth, self.clear(), stencil)
    }

    /// How a pass that starts the depth buffer clears it: to the far depth of the
    /// convention, which without a parameter waits for the format.
    pub fn clear(self) -> AspectAccess<f32> {
        match self.reversed_z {
            Some(reversed_z) => AspectAccess::Clear(far_depth(named(reversed_z))),
            None => {
                AspectAccess::ClearByFormat(ByFormat(|format| far_depth(format_convention(format))))
            }
        }
    }
}

/// Binds `depth` as the attachment of a pass that draws every depth later passes test:
/// depth and stencil (where the format has one: nothing such a pass's readers test)
/// overwritten, not cleared ([`AspectAccess::Overwrite`]: a multisampled clear costs the
/// H200 as much as a full-screen pass). Returns the written version.
pub(crate) fn overwrite(pass: &mut PassBuilder<'_>, depth: TextureHandle) -> TextureHandle {
    let stencil = stencil_where_present(pass, depth, AspectAccess::Overwrite);
    pass.depth_stencil(depth, AspectAccess::Overwrite, stencil)
}

/// `access` for the stencil of `depth`, or `Absent` where its format has none.
fn stencil_where_present(
    pass: &PassBuilder<'_>,
    depth: TextureHandle,
    access: AspectAccess<u32>,
) -> AspectAccess<u32> {
    match pass.resource(depth).texture().map(|d| d.format) {
        Some(format) if !format.has_stencil_aspect() => AspectAccess::Absent,
        _ => access,
    }
}

/// The convention a `reversed_z` parameter names.
fn named(reversed_z: bool) -> DepthConvention {
    match reversed_z {
        true => DepthConvention::ReversedZ,
        false => DepthConvention::Standard,
    }
}

/// Reversed-Z for float depth, standard Z for unorm depth (see the module
/// documentation).
fn format_convention(format: TextureFormat) -> DepthConvention {
    match format {
        TextureFormat::Depth32Float | TextureFormat::Depth32FloatStencil8 => {
            DepthConvention::ReversedZ
        }
        _ => DepthConvention::Standard,
    }
}

/// The depth a depth-stencil is cleared to, and the clip depth of the far plane.
pub(crate) fn far_depth(convention: DepthConvention) -> f32 {
    match convention {
        DepthConvention::ReversedZ => 0.0,
        DepthConvention::Standard => 1.0,
    }
}

#[cfg(test)]
mod tests {
    use rgraph_core::types::TextureFormat as F;
    use rgraph_core::AspectAccess;

    use super::DepthRule;
    use rgraph_scene::DepthConvention::{ReversedZ, Standard};

    #[test]
    fn without_a_parameter_float_depth_is_reversed_and_unorm_depth_is_not() {
        let rule = DepthRule::new(None);
        for (format, convention, far) in [
            (F::Depth32FloatStencil8, ReversedZ, 0.0),
            (F::Depth32Float, ReversedZ, 0.0),
            (F::Depth24PlusStencil8, Standard, 1.0),
            (F::Depth24Plus, Standard, 1.0),
            (F::Depth16Unorm, Standard, 1.0),
        ] {
            assert_eq!(rule.convention(format), convention, "{format:?}");
            let AspectAccess::ClearByFormat(by) = rule.clear() else {
                panic!("the clear waits for the format");
            };
            assert_eq!(by.value(format), far, "{format:?}");
        }
    }

    #[test]
    fn an_explicit_parameter_holds_for_every_format() {
        for format in [F::Depth32FloatStencil8, F::Depth24PlusStencil8] {
            assert_eq!(DepthRule::new(Some(true)).convention(format), ReversedZ);
            assert_eq!(DepthRule::new(Some(false)).convention(format), Standard);
        }
        assert_eq!(DepthRule::new(Some(true)).clear(), AspectAccess::Clear(0.0));
        assert_eq!(
            DepthRule::new(Some(false)).clear(),
            AspectAccess::Clear(1.0)
        );
    }
}
