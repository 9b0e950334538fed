//! Seed 001's work figures for pipelines with particle passes (Table 23-1's columns):
//! particle pixels, the fragments the `particles` passes shade, and image-processing
//! pixels, those of `depth_downsample`, `particle_edges` and `composite_particles`.
//! Counted on the CPU from the scene's particles, its camera and the plan's render sizes
//! (lavapipe's pipeline statistics count fragments wrongly: ../shared/notes/wgpu30.md).

use rgraph_core::Plan;
use rgraph_scene::{billboard_pixels, Scene};
use serde::Serialize;

/// The output of the mixed-resolution pipeline that shows its edge mask (red on black, at
/// the output's size).
pub const PARTICLE_EDGES_OUTPUT: &str = "debug.particle_edges";

#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ParticleWork {
    /// Billboard pixels over every particle pass, overlaps counted as often as they
    /// overlap.
    pub particle_pixels: f64,
    /// Pixels of the depth downsample, edge detection and composite passes.
    pub image_processing_pixels: f64,
    /// The passes of the technique (particle passes and image processing), whose GPU
    /// times add up to its cost apart from the opaque frame's.
    pub passes: Vec<String>,
    /// How the full-resolution pass of mixed resolution was counted: its billboard pixels
    /// times the edge mask's share of the pixels (`debug.particle_edges`), an estimate:
    /// the composite leaves a little more than the mask to it. `null` without such a pass.
    pub stencilled: Option<String>,
}

impl ParticleWork {
    /// For `plan`, whose passes `plugin` names the plugins of, drawing `scene`'s particles
    /// through its camera; `edge_share` is the mixed pipeline's edge mask's share, when
    /// it has one. `None` for a plan without particle passes.
    pub fn of(
        plan: &Plan,
        plugin: impl Fn(&str) -> Option<String>,
        scene: &Scene,
        edge_share: Option<f64>,
    ) -> Option<ParticleWork> {
        let mut work = ParticleWork {
            particle_pixels: 0.0,
            image_processing_pixels: 0.0,
            passes: Vec::new(),
            stencilled: None,
        };
        for pass in &plan.passes {
            let Some(size) = pass
                .color
                .first()
                .and_then(|c| plan.resource(c.resource).texture.as_ref())
                .map(|t| (t.width, t.height))
            else {
                continue;
            };
            match plugin(&pass.name).as_deref() {
                Some("particles") => {
                    work.passes.push(pass.name.clone());
                    let pixels = billboard_pixels(scene.particles(), &scene.camera, size);
                    let share = match (&pass.depth_stencil, edge_share) {
                        (None, _) => 1.0,
                        (Some(_), Some(share)) => {
                            work.stencilled = Some(format!(
                                "\"{}\": billboard pixels times the edge mask's share, {share:.4}",
                                pass.name
                            ));
                            share
                        }
                        (Some(_), None) => {
                            work.stencilled = Some(format!(
                                "\"{}\": every billboard pixel (no edge mask to count the \
                                 stencilled share with)",
                                pass.name
                            ));
                            1.0
                        }
                    };
                    work.particle_pixels += pixels * share;
                }
                Some("depth_downsample" | "particle_edges" | "composite_particles") => {
                    work.passes.push(pass.name.clone());
                    work.image_processing_pixels += f64::from(size.0) * f64::from(size.1);
                }
                _ => {}
            }
        }
        (!work.passes.is_empty()).then_some(work)
    }
}
