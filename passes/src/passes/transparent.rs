//! `transparent` and `composite_transparent`: alpha BLEND surfaces, drawn after the opaque
//! scene is lit (deferred or forward) and composited onto its resolved HDR image, so every
//! pipeline renders them alike.
//!
//! ```ron
//! (name: "transparent", plugin: "transparent",
//!  params: (shading: pixel,      // the default; or sample (the reference); reversed_z optional
//!           extent: blended),    // or `full` (the default): where the accumulation begins
//!  inputs: {
//!      "depth": "depth",          // the opaque passes' depth, any sample count: read-only
//!      "shadows": "shadow_atlas", // optional: shadow_maps's atlas, which scales each
//!  },                             // shadowed light (group 2), as forward's does
//!  outputs: { "accum": "transparent" }),   // rgba16float, the depth's sample count
//! (name: "composite transparent", plugin: "composite_transparent",
//!  inputs: { "accum": "transparent", "resolved": "resolved_hdr" }, // rgba16float, 1x, the
//!  outputs: { "resolved": "resolved" })                            // accumulation's size
//! ```
//!
//! The shipped pipelines name the resolved texture `resolved_hdr` and the composite's
//! version of it `resolved`, so `resolved` (what tone mapping, auto exposure and tests
//! read) is the final image whether or not the composite runs.
//!
//! **The transparent pass** draws the scene's BLEND meshes (which the `gbuffer` and
//! `forward` passes skip) back to front, each mesh at the distance of its bounds' centre
//! from the camera, sorted on the CPU every frame; a mesh is not sorted against itself,
//! so its own overlapping triangles blend in index order, and intersecting meshes blend
//! in the order of their centres. Each fragment is shaded as the `forward` pass shades
//! (forward.wgsl's vertex stages and `shade_surface`): the same material model, every
//! light of the scene, each shadowed light scaled by its shadow maps where the pass reads
//! the atlas (a blended surface receives shadows as an opaque one does; it casts none:
//! `shadow_maps` draws the opaque and masked meshes), emission added, unlit materials
//! their base colour, double-sided back faces lit from their side. `shading: sample` shades every covered sample at its
//! own position, as the supersampled reference needs. Depth is tested against the
//! multisampled depth of the opaque passes, attached read-only (both aspects): a blended
//! surface behind an opaque one is hidden per sample, and blended surfaces never hide
//! each other. The accumulation target begins as (0, 0, 0, 1) and is blended as seed
//! 001 accumulates off-screen particles: rgb by conventional alpha blending
//! (`src * a + dst * (1 - a)`), alpha multiplied by `1 - a`; per sample it ends as
//! `C`, the blended surfaces over black, and `T`, the product of their transmittances.
//! Listing `accum` in `inputs` too draws over an accumulation instead of beginning one
//! (another layer of blended geometry, such as particles).
//!
//! With `extent: full` the accumulation is cleared, every pixel of it. With `extent:
//! blended` only the pixels the blended meshes may cover begin as (0, 0, 0, 1) (a
//! scissored draw over their rectangle on screen, [`Extent::Blended`]), and nothing is
//! drawn when none is in view: the rest of the target is undefined, and the composite
//! never reads it. A multisampled clear goes through the ROPs, which on the H200 cost as
//! much as a full-screen pass: 4.72 of this pass's 4.76 ms on FlightHelmet at 3840x2160
//! 4x (docs/design/compute-raster.md, run visibility-merged), where the lenses cover a small
//! part of the output.
//!
//! **The composite** is a full-screen draw onto the single-sampled HDR image (`resolved`,
//! modified in place) that reads each pixel's samples of the accumulation and outputs
//! their mean colour and mean transmittance, blended with source factor one and
//! destination factor source alpha: `resolved * mean(T) + mean(C)`, before tone mapping.
//! It draws only the pixels the blended meshes may cover, as `extent: blended` begins
//! them: elsewhere T = 1 and C = 0 leave the image exactly as it is.
//!
//! What that costs in exactness: the exact pixel is the mean over samples of
//! `hdr_s * T_s + C_s`; the composite computes `mean(hdr) * mean(T) + mean(C)`, which
//! differs by the covariance of `hdr_s` and `T_s` over the pixel's samples. Both vary
//! only on MSAA edges where a blended surface's coverage changes among samples whose
//! opaque colours differ too (an opaque silhouette in front of a panel, or a panel's own
//! edge across an opaque edge): there the transmittance is spread evenly over the
//! pixel's opaque colours instead of over the samples it belongs to, e.g. an opaque
//! object covering half of a pixel in front of a panel of alpha `a` comes out
//! `a * (background - object) / 4` off. Pixels whose opaque samples agree (inside
//! surfaces) or whose transmittance is uniform (inside a panel) are exact. The pixel
//! still lies between its surfaces' values, so edges stay antialiased. Pipelines
//! without a multisampled lit HDR image (tiled lighting resolves in its compute pass)
//! could not do better without keeping one; the same composite everywhere keeps the
//! bench comparing like with like.
//!
//! Pipelines whose resolve weights samples by their tone-mapped brightness (`resolve`
//! with `mode: tonemapped`, `light_tiled` with `resolve: tonemapped`) still output
//! linear HDR (the weighting is undone), so the composite applies unchanged after them;
//! it box-averages the blended layer itself, so on a pixel where a very bright and a
//! dark transparent sample meet the blended layer gets the plain average, not the
//! luminance-weighted one.

use serde::Deserialize;

use rgraph_core::file::{Plugin, PluginError, Slots};
use rgraph_core::types::{BlendComponent, BlendFactor, BlendOperation, BlendState};
use rgraph_core::{AspectAccess, ColorLoad, PassBuilder, PassKind};

use super::forward::{Shading, DEPTH};
use super::gbuffer::opaque_black;
use crate::common::depth::DepthRule;
use crate::common::extent::Extent;
use crate::common::fullscreen::Fullscreen;
use crate::common::plugin::Shared;
use crate::common::scene_draw::SceneDraw;
use crate::common::shadows;
use crate::common::textures::{self, Want};
use crate::shaders;
use crate::variant::GatedShader;

pub struct Transparent(pub(crate) Shared);
pub struct CompositeTransparent(pub(crate) Shared);

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TransparentParams {
    #[serde(default)]
    pub shading: Shading,
    /// Fixes the depth convention; left out, it follows the depth format the compile
    /// picks, as the opaque passes' does: they must agree.
    #[serde(default)]
    pub reversed_z: Option<bool>,
    /// Which pixels a fresh accumulation begins at (see the module documentation).
    #[serde(default)]
    pub extent: Extent,
}

#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CompositeTransparentParams {}

impl Plugin for Transparent {
    const NAME: &'static str = "transparent";
    type Params = TransparentParams;

    fn kind(&self, _: &TransparentParams) -> PassKind {
        PassKind::Render
    }

    fn setup(
        &self,
        params: TransparentParams,
        pass: &mut PassBuilder<'_>,
        slots: &mut Slots<'_>,
    ) -> Result<(), PluginError> {
        let want = Want::new("the opaque passes' depth", DEPTH);
        let (depth, desc) = textures::input(slots, pass, "depth", want)?;
        pass.depth_stencil(depth, AspectAccess::ReadOnly, AspectAccess::ReadOnly);
        let want = Want::new("the transparent accumulation", textures::HDR).samples(desc.samples);
        // Transmittance 1 where nothing blended is drawn: the composite leaves those pixels.
        // Begun by a draw over the blended meshes' rectangle instead of a clear, where the
        // extent says so.
        let fresh = match params.extent {
            Extent::Full => ColorLoad::Clear(opaque_black()),
            Extent::Blended => ColorLoad::Overwrite,
        };
        let (accum, _) = textures::attached_output(slots, pass, "accum", want, fresh)?;
        let begin = params.extent == Extent::Blended && !slots.modifies("accum");
        let shadows = shadows::input(slots, pass)?;
        let filter = self.0.overrides.shadows.filter;
        let draw = shadows::variants(shadows::optional(slots), shadows, |shadows| {
            // Group 1 is the material's: the atlas is bound in group 2, as forward's.
            let generated = shadows::wgsl(shadows, 2, filter);
            let source = shaders::TRANSPARENT.compose_with(desc.samples, &generated)?;
            Ok(SceneDraw {
                blended: true,
                begin_blended: begin.then_some("fs_accumulation_start"),
                shadows: shadows.copied(),
                ..SceneDraw::new(
                    "transparent",
                    GatedShader::Transparent,
                    source.source().to_owned(),
                    DepthRule::new(params.reversed_z),
                    vec![accum],
                    depth,
                    params.shading.stages(true),
                )
            })
        })?;
        self.0.record(pass, draw);
        Ok(())
    }
}

/// `hdr * T + C` from the composite's output (C, T): see the module documentation. The
/// target's alpha, the background's transmittance where a `background` pass wrote it, is
/// multiplied by T: what still shows of the background. The particle composite blends
/// the same way.
pub(crate) const UNDER_TRANSMITTANCE: BlendState = BlendState {
    color: BlendComponent {
        src_factor: BlendFactor::One,
        dst_factor: BlendFactor::SrcAlpha,
        operation: BlendOperation::Add,
    },
    alpha: BlendComponent {
        src_factor: BlendFactor::Zero,
        dst_factor: BlendFactor::SrcAlpha,
        operation: BlendOperation::Add,
    },
};

impl Plugin for CompositeTransparent {
    const NAME: &'static str = "composite_transparent";
    type Params = CompositeTransparentParams;

    fn kind(&self, _: &CompositeTransparentParams) -> PassKind {
        PassKind::Render
    }

    fn setup(
        &self,
        _: CompositeTransparentParams,
        pass: &mut PassBuilder<'_>,
        slots: &mut Slots<'_>,
    ) -> Result<(), PluginError> {
        let want = Want::new("the transparent accumulation", textures::HDR);
        let (accum, accum_desc) = textures::sampled(slots, pass, "accum", want, 0)?;
        let want = Want::new("the resolved HDR image", textures::HDR).samples(1);
        let mut modifies = true;
        let (target, desc) = textures::output(slots, pass, "resolved", want, |pass, h, m| {
            modifies = m;
            pass.color_output(h, ColorLoad::Load)
        })?;
        textures::must_modify(slots, "resolved", modifies, "blends onto it")?;
        if desc.size != accum_desc.size {
            return Err(PluginError::Slot {
                slot: "resolved".to_owned(),
                resource: slots.resource("resolved").unwrap_or("resolved").to_owned(),
                why: format!(
                    "is {:?}, but the accumulation it composites (\"{}\") is {:?}: the \
                     composite reads the accumulation's pixel under each of its pixels",
                    desc.size,
                    slots.resource("accum").unwrap_or("accum"),
                    accum_desc.size
                ),
            });
        }
        let source = shaders::COMPOSITE
            .compose(accum_desc.samples)?
            .source()
            .to_owned();
        let draw = Fullscreen {
            extent: Extent::Blended,
            blend: Some(UNDER_TRANSMITTANCE),
            ..Fullscreen::new(
                "composite transparent",
                source,
                "fs_composite",
                vec![accum],
                Some(target),
            )
        };
        self.0.record(pass, draw);
        Ok(())
    }
}
