//! `particle_edges`: the Sobel edge detector of mixed-resolution particles (seed 001
//! §23.6.1), on the off-screen particle colour, transmittance and emissive targets.
//!
//! ```ron
//! (name: "particle edges", plugin: "particle_edges",
//!  params: (threshold: 1.0),   // the default
//!  inputs: { "color": "particle_color", "additive": "particle_additive" },
//!  outputs: { "edges": "particle_edges" })   // r8unorm at their size: 1 on edges
//! ```
//!
//! A full-screen draw at the off-screen size: each of the three signals (colour
//! luminance and emissive luminance as `x / (1 + x)`, transmittance as it is) is
//! filtered with the 3x3 Sobel kernels, and a pixel is an edge where any gradient's
//! magnitude exceeds `threshold` (a step of 1 across a pixel gives 4; the default, 1,
//! marks about 4% of the off-screen pixels of builtin:smoke at scale 2 and 11% at 4). Edges are where
//! the upsampled image would look blocky: `composite_particles` leaves those areas to a
//! second, full-resolution particle pass.

use serde::Deserialize;

use rgraph_core::file::{Plugin, PluginError, Slots};
use rgraph_core::{PassBuilder, PassKind};

use super::particles::{same_size, EDGES};
use crate::common::fullscreen::Fullscreen;
use crate::common::plugin::Shared;
use crate::common::textures::{self, Want};
use crate::shaders;

pub struct ParticleEdges(pub(crate) Shared);

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ParticleEdgesParams {
    /// The Sobel magnitude above which a pixel is an edge: finite and positive.
    #[serde(default = "default_threshold")]
    pub threshold: f32,
}

fn default_threshold() -> f32 {
    1.0
}

impl Plugin for ParticleEdges {
    const NAME: &'static str = "particle_edges";
    type Params = ParticleEdgesParams;

    fn kind(&self, _: &ParticleEdgesParams) -> PassKind {
        PassKind::Render
    }

    fn setup(
        &self,
        params: ParticleEdgesParams,
        pass: &mut PassBuilder<'_>,
        slots: &mut Slots<'_>,
    ) -> Result<(), PluginError> {
        if !(params.threshold.is_finite() && params.threshold > 0.0) {
            return Err(PluginError::Invalid(format!(
                "threshold {} must be finite and positive (a Sobel magnitude: a step of 1 \
                 across a pixel gives 4)",
                params.threshold
            )));
        }
        let want = Want::new("the off-screen particle colour", textures::HDR).samples(1);
        let (color, color_desc) = textures::sampled(slots, pass, "color", want, 0)?;
        let want = Want::new("the off-screen emissive particles", textures::HDR).samples(1);
        let (additive, additive_desc) = textures::sampled(slots, pass, "additive", want, 1)?;
        same_size(slots, ("additive", &additive_desc), ("color", &color_desc))?;
        let want = Want::new("the particle edges", EDGES).samples(1);
        let (edges, desc) = textures::color_output(slots, pass, "edges", want, [0.0; 4])?;
        same_size(slots, ("edges", &desc), ("color", &color_desc))?;
        let source = shaders::PARTICLE_EDGES.compose(1)?.source().to_owned();
        let inputs = vec![color, additive];
        let draw = Fullscreen {
            constants: vec![("THRESHOLD", f64::from(params.threshold))],
            ..Fullscreen::new("particle edges", source, "fs_sobel", inputs, Some(edges))
        };
        self.0.record(pass, draw);
        Ok(())
    }
}
