//! What one pipeline measured on one scene (a row of results.json): what the measuring
//! writes and the results, the table and the charts read.

use serde::Serialize;

use super::flag::{Created, Flag};
use super::image_error::ImageError;
use super::memory::Memory;
use super::particle_work::ParticleWork;
use super::specialisation::Specialisation;
use super::stats::Spread;
use super::work::Work;

#[derive(Debug, Serialize)]
pub struct Figures {
    /// The most samples of any texture the pipeline uses.
    pub samples: u32,
    /// From the first pass's begin timestamp to the last one's end: the median of the
    /// round medians, and their spread (stats.rs); `null` when the device has no
    /// timestamp queries.
    pub gpu_frame_ms: Option<Spread>,
    /// Set when `gpu_frame_ms.spread` exceeds 5%, with the reasons the bench knows.
    pub flag: Option<Flag>,
    /// Pipelines and shader modules the measured frames created, per round that
    /// created any (empty when the warmup created them all, as it should).
    pub created_while_measured: Vec<Created>,
    /// CPU time to record all passes (callbacks included), over the rounds as the GPU
    /// time is.
    pub cpu_record_ms: Option<Spread>,
    /// Median GPU frame time over deferred_noaa's on the same scene in this run.
    pub ratio_to_noaa: Option<f64>,
    /// Executed passes in order.
    pub passes: Vec<PassFigures>,
    pub memory: Memory,
    pub work: Work,
    /// Against the reference; `null` without one.
    pub image_error: Option<ImageError>,
    /// The general plan's figures, when the scene's plan is specialised (all other
    /// figures are the scene's plan's).
    pub specialisation: Option<Specialisation>,
    /// Particle and image-processing pixels, for a plan with particle passes.
    pub particles: Option<ParticleWork>,
}

#[derive(Debug, Serialize)]
pub struct PassFigures {
    pub name: String,
    pub kind: String,
    pub gpu_ms: Option<Spread>,
    pub cpu_ms: Option<Spread>,
}
