//! `edge_stencil`: marks edge pixels, those whose samples hold different surfaces, with
//! stencil bit 0x80, for `light_edge` to shade per sample and `light_nonedge` per pixel.
//!
//! ```ron
//! (name: "edges", plugin: "edge_stencil",
//!  params: (detector: compare,   // the default; or centroid | coverage | all | none
//!           depth_threshold: 0.01, normal_threshold: 0.95, albedo_threshold: 0.05),
//!  inputs: {
//!      "albedo": "albedo", "normal": "normal", "material": "material",
//!      "view_depth": "view_depth",   // compare reads all four; centroid and coverage
//!                                    // only "material"; all and none none of them
//!      "depth": "depth",             // the G-buffer's depth-stencil ...
//!  },
//!  outputs: { "depth": "depth_edges" })   // ... whose stencil the pass marks
//! ```
//!
//! A full-screen triangle shaded once per pixel, with depth attached read-only and the
//! stencil written through mask 0x80 wherever the shader does not discard. The G-buffer
//! is read with `textureLoad`; its depth aspect cannot be, as the stencil is written in
//! this pass, hence the `view_depth` target. Detectors:
//! - `compare`: some sample differs from sample 0 in view depth by more than
//!   `depth_threshold` times the larger depth, in normal by a cosine below
//!   `normal_threshold`, in an albedo channel by more than `albedo_threshold`, or in its
//!   material flags (lit, unlit, background);
//! - `centroid`: some sample's fragment had its centroid away from the pixel center
//!   (seed 000's centroid trick, recorded by the G-buffer pass; an implementation may
//!   put the centroid at the center whenever that is covered, so it can miss edges;
//!   whether it sees intersection edges is the implementation's too: lavapipe takes the
//!   centroid from the coverage left after its early depth test and marks them,
//!   tests/deferred_detectors.rs);
//! - `coverage`: some sample's fragment covered only part of the pixel
//!   (`@builtin(sample_mask)` as a G-buffer input; misses intersection edges, where both
//!   surfaces cover every sample);
//! - `all`: every pixel, i.e. per-sample shading everywhere; `none`: no pixel.
//!
//! With one sample per pixel the pass is omitted from every plan (`explain` says so): a
//! pixel then holds one surface, so no detector has an edge to find, and `all`'s
//! per-sample shading is `light_nonedge`'s per-pixel shading. One pipeline file thus
//! serves every sample count (bench --sweep samples) without idle passes.

use serde::Deserialize;

use graph_core::file::{Plugin, PluginError, Slots};
use graph_core::{AspectAccess, PassBuilder, PassKind};

use super::fullscreen::Fullscreen;
use super::light::GBUFFER_INPUTS;
use super::textures::{self, Want};
use super::Shared;
use crate::shaders;

pub struct EdgeStencil(pub(crate) Shared);

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EdgeStencilParams {
    #[serde(default)]
    pub detector: Detector,
    #[serde(default = "depth_threshold")]
    pub depth_threshold: f32,
    #[serde(default = "normal_threshold")]
    pub normal_threshold: f32,
    #[serde(default = "albedo_threshold")]
    pub albedo_threshold: f32,
}

fn depth_threshold() -> f32 {
    0.01
}
fn normal_threshold() -> f32 {
    0.95
}
fn albedo_threshold() -> f32 {
    0.05
}

#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Detector {
    #[default]
    Compare,
    Centroid,
    Coverage,
    All,
    None,
}

/// `EDGE_CENTROID` and `EDGE_COVERAGE` in common.wgsl.
const EDGE_CENTROID: f64 = 128.0;
const EDGE_COVERAGE: f64 = 64.0;

impl EdgeStencilParams {
    fn check(&self) -> Result<(), PluginError> {
        let bad = |name: &str, value: f32, range: &str| {
            PluginError::Invalid(format!("{name} must be {range}, got {value}"))
        };
        if !(self.depth_threshold.is_finite() && self.depth_threshold >= 0.0) {
            return Err(bad(
                "depth_threshold",
                self.depth_threshold,
                "finite and >= 0",
            ));
        }
        if !(-1.0..=1.0).contains(&self.normal_threshold) {
            return Err(bad(
                "normal_threshold",
                self.normal_threshold,
                "a cosine in [-1, 1]",
            ));
        }
        if !(self.albedo_threshold.is_finite() && self.albedo_threshold >= 0.0) {
            return Err(bad(
                "albedo_threshold",
                self.albedo_threshold,
                "finite and >= 0",
            ));
        }
        Ok(())
    }
}

impl Plugin for EdgeStencil {
    const NAME: &'static str = "edge_stencil";
    type Params = EdgeStencilParams;

    fn kind(&self, _: &EdgeStencilParams) -> PassKind {
        PassKind::Render
    }

    fn setup(
        &self,
        params: EdgeStencilParams,
        pass: &mut PassBuilder<'_>,
        slots: &mut Slots<'_>,
    ) -> Result<(), PluginError> {
        params.check()?;
        let want = Want::new("the G-buffer's depth-stencil", textures::DEPTH_STENCIL);
        let mut modifies = true;
        let (depth, desc) = textures::output(slots, pass, "depth", want, |pass, h, m| {
            modifies = m;
            pass.depth_stencil(h, AspectAccess::ReadOnly, AspectAccess::Load)
        })?;
        textures::must_modify(slots, "depth", modifies, "marks edges in its stencil")?;
        let reads: &[&str] = match params.detector {
            Detector::Compare => &["albedo", "normal", "material", "view_depth"],
            Detector::Centroid | Detector::Coverage => &["material"],
            Detector::All | Detector::None => &[],
        };
        let mut inputs = Vec::new();
        for (slot, what, formats, binding) in GBUFFER_INPUTS {
            if reads.contains(&slot) {
                let want = Want::new(what, formats).samples(desc.samples);
                inputs.push(textures::sampled(slots, pass, slot, want, binding)?.0);
            }
        }
        let (entry, constants) = match params.detector {
            Detector::Compare => (
                "fs_compare",
                vec![
                    ("DEPTH_THRESHOLD", f64::from(params.depth_threshold)),
                    ("NORMAL_THRESHOLD", f64::from(params.normal_threshold)),
                    ("ALBEDO_THRESHOLD", f64::from(params.albedo_threshold)),
                ],
            ),
            Detector::Centroid => ("fs_flag", vec![("EDGE_BIT", EDGE_CENTROID)]),
            Detector::Coverage => ("fs_flag", vec![("EDGE_BIT", EDGE_COVERAGE)]),
            Detector::All => ("fs_all", Vec::new()),
            // The stencil stays as the G-buffer pass cleared it.
            Detector::None => return Ok(()),
        };
        if desc.samples == 1 {
            pass.omit(super::ONE_SAMPLE);
            return Ok(());
        }
        let draw = Fullscreen {
            label: "edge_stencil",
            source: shaders::EDGE.compose(desc.samples)?.source().to_owned(),
            entry,
            constants,
            inputs,
            reads_scene: false,
            target: None,
            stencil_mark: Some(depth),
        };
        self.0.render(pass, draw);
        Ok(())
    }
}
