//! Scene analysis: what a scene needs from a pipeline, found on the CPU before anything
//! is uploaded. [`Features::of`] names the features graph-file conditions test (a
//! pipeline compiled for them drops the passes and G-buffer channels the scene does not
//! use, and `shallow_depth` picks the smaller depth format); [`DepthRange::of`] and
//! [`SmallestFeature::of`] measure the depth and detail the scene puts on screen. The pass
//! crate turns the features into shader variants (only the code paths a scene uses).

mod depth;
mod feature_size;
mod features;

pub use depth::{DepthRange, SHALLOW_STEP};
pub use feature_size::SmallestFeature;
pub use features::Features;

use crate::Scene;

/// Everything analysis finds about one scene at one output size.
#[derive(Clone, Debug, PartialEq)]
pub struct Analysis {
    /// The features the scene uses, by the names graph-file conditions test.
    pub features: Features,
    /// `None` when no geometry lies between the camera's planes.
    pub depth: Option<DepthRange>,
    /// [`DepthRange::unorm24_step`] for the scene's camera: what decides
    /// `shallow_depth`.
    pub unorm24_step: Option<f64>,
    /// `None` when no triangle edge lies between the camera's planes.
    pub smallest: Option<SmallestFeature>,
}

impl Analysis {
    /// Analyses `scene` as rendered at `output` (width, height) pixels.
    pub fn of(scene: &Scene, output: (u32, u32)) -> Analysis {
        let depth = DepthRange::of(scene);
        Analysis {
            features: Features::of(scene),
            depth,
            unorm24_step: depth.map(|range| range.unorm24_step(&scene.camera.projection)),
            smallest: SmallestFeature::of(scene, output),
        }
    }
}
