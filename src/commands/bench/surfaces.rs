//! The lower bound of shading work: one shading per distinct surface in a pixel, counted
//! at 4x from the G-buffer by bench/graphs/unique_surfaces.ron (its comments define a
//! surface). Per pixel the bound is the count, and 1 where it is 0 (a full-screen deferred
//! pass runs once even where no geometry is), so it compares with shaded samples per pixel.

use std::path::Path;
use std::sync::Arc;

use rgraph_passes::Host;
use serde::Serialize;

use super::candidates::Candidate;
use super::measure::Setup;
use crate::frame::FrameError;

/// The measurement graph, relative to the repository root (as pipelines/ is).
pub const GRAPH: &str = "bench/graphs/unique_surfaces.ron";
const OUTPUT: &str = "surfaces";
/// The sample count the graph counts surfaces at.
pub const SAMPLES: u32 = 4;

#[derive(Clone, Debug, Serialize)]
pub struct UniqueSurfaces {
    /// Mean over pixels of max(1, distinct surfaces among the pixel's samples).
    pub per_pixel: f64,
    pub samples: u32,
    pub graph: String,
}

/// Renders the graph on `host`'s scene and averages the per-pixel counts.
pub fn measure(setup: &Setup, host: &Arc<Host>) -> Result<UniqueSurfaces, FrameError> {
    let image = setup.render(&Candidate::file(Path::new(GRAPH)), host, OUTPUT)?;
    let total: u64 = image.pixels().map(|p| u64::from(p.0[0].max(1))).sum();
    let pixels = (image.width() as u64 * image.height() as u64).max(1);
    Ok(UniqueSurfaces {
        per_pixel: total as f64 / pixels as f64,
        samples: SAMPLES,
        graph: GRAPH.into(),
    })
}
