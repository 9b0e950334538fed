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
//! this pass, hence the `view_depth` target. The detectors and thresholds are
//! [`EdgeDetection`]'s, which `light_tiled` shares.
//!
//! With one sample per pixel the pass is omitted from every plan (`explain` says so): a
//! pixel then holds one surface, so no detector has an edge to find, and `all`'s
//! per-sample shading is `light_nonedge`'s per-pixel shading. One pipeline file thus
//! serves every sample count (bench --sweep samples) without idle passes.

use rgraph_core::file::{Plugin, PluginError, Slots};
use rgraph_core::{AspectAccess, PassBuilder, PassKind};

use crate::common::edge_detection::{Detector, EdgeDetection};
use crate::common::fullscreen::Fullscreen;
use crate::common::plugin::{Shared, ONE_SAMPLE};
use crate::common::textures::{self, Want, GBUFFER_INPUTS};
use crate::shaders;

pub struct EdgeStencil(pub(crate) Shared);

impl Plugin for EdgeStencil {
    const NAME: &'static str = "edge_stencil";
    type Params = EdgeDetection;

    fn kind(&self, _: &EdgeDetection) -> PassKind {
        PassKind::Render
    }

    fn setup(
        &self,
        params: EdgeDetection,
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
        let mut inputs = Vec::new();
        for (slot, what, formats, binding) in GBUFFER_INPUTS {
            if params.reads().contains(&slot) {
                let want = Want::new(what, formats).samples(desc.samples);
                inputs.push(textures::sampled(slots, pass, slot, want, binding)?.0);
            }
        }
        let entry = match params.detector {
            Detector::Compare => "fs_compare",
            Detector::Centroid | Detector::Coverage => "fs_flag",
            Detector::All => "fs_all",
            // The stencil stays as the G-buffer pass cleared it.
            Detector::None => return Ok(()),
        };
        if desc.samples == 1 {
            pass.omit(ONE_SAMPLE);
            return Ok(());
        }
        let source = shaders::EDGE.compose(desc.samples)?.source().to_owned();
        let draw = Fullscreen {
            constants: params.constants(),
            stencil_mark: Some(depth),
            ..Fullscreen::new("edge_stencil", source, entry, inputs, None)
        };
        self.0.record(pass, draw);
        Ok(())
    }
}
