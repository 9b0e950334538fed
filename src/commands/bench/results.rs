//! Everything a bench measured, as written to results.json (and read by the table and the
//! charts). Figures that could not be measured are `null`, with the reason nearby.

use serde::Serialize;

use super::image_error::ImageError;
use super::machine::{Adapter, Machine};
use super::memory::Memory;
use super::particle_work::ParticleWork;
use super::reference::Reference;
use super::scene::SceneSummary;
use super::specialisation::Specialisation;
use super::stats::Spread;
use super::sweep::SweepPoint;
use super::work::Work;
use crate::cli::Sweep;

/// Bumped when a field changes meaning or moves.
pub const SCHEMA: u32 = 2;

#[derive(Debug, Serialize)]
pub struct Results {
    pub schema: u32,
    /// The command line that produced this file.
    pub command: String,
    pub machine: Machine,
    pub adapter: Adapter,
    pub git_commit: String,
    /// When the run started: UTC, RFC 3339.
    pub timestamp: String,
    /// The size asked for (a resolution sweep replaces it: see each row's `sweep`).
    pub resolution: [u32; 2],
    /// What `--sweep` varied, if anything.
    pub sweep: Option<Sweep>,
    pub frames: u32,
    pub warmup: u32,
    /// What errors are measured against; `null` when nothing could be.
    pub reference: Option<Reference>,
    /// Things the reader should know: skipped files, substitutes, unmeasured figures.
    pub notes: Vec<String>,
    /// Per scene: its images folder and its edge pixels.
    pub scenes: Vec<SceneSummary>,
    /// One per scene and pipeline (and sweep value), error rows included.
    pub rows: Vec<Row>,
}

#[derive(Debug, Serialize)]
pub struct Row {
    /// The scene spec, e.g. "builtin:dense".
    pub scene: String,
    /// The pipeline's name: its file stem (and variant).
    pub pipeline: String,
    pub file: String,
    /// "ok", or "error" with `message` set and `figures` null.
    pub status: &'static str,
    /// The sweep value this row was measured at; `null` outside sweeps.
    pub sweep: Option<SweepPoint>,
    pub message: Option<String>,
    pub figures: Option<Figures>,
}

#[derive(Debug, Serialize)]
pub struct Figures {
    /// The most samples of any texture the pipeline uses.
    pub samples: u32,
    /// From the first pass's begin timestamp to the last one's end, per measured frame;
    /// `null` when the device has no timestamp queries.
    pub gpu_frame_ms: Option<Spread>,
    /// CPU time to record all passes (callbacks included), per measured frame.
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

impl Row {
    pub fn ok(scene: &str, pipeline: &str, file: &str, figures: Figures) -> Row {
        Row {
            scene: scene.into(),
            pipeline: pipeline.into(),
            file: file.into(),
            status: "ok",
            sweep: None,
            message: None,
            figures: Some(figures),
        }
    }

    pub fn error(scene: &str, pipeline: &str, file: &str, message: String) -> Row {
        Row {
            scene: scene.into(),
            pipeline: pipeline.into(),
            file: file.into(),
            status: "error",
            sweep: None,
            message: Some(message),
            figures: None,
        }
    }
}

/// Each measured row's median GPU frame time over the `baseline` pipeline's on the same
/// scene and at the same sweep value.
pub fn ratios_to_baseline(rows: &mut [Row], baseline: &str) {
    let median = |row: &Row| {
        row.figures
            .as_ref()?
            .gpu_frame_ms
            .as_ref()
            .map(|s| s.median)
    };
    let key = |row: &Row| (row.scene.clone(), row.sweep.as_ref().map(|p| p.value));
    let baselines: Vec<_> = rows
        .iter()
        .filter(|r| r.pipeline == baseline)
        .filter_map(|r| Some((key(r), median(r)?)))
        .collect();
    for row in rows.iter_mut() {
        let base = baselines.iter().find(|(k, _)| *k == key(row)).map(|b| b.1);
        let ratio = base.zip(median(row)).map(|(b, m)| m / b);
        if let Some(figures) = &mut row.figures {
            figures.ratio_to_noaa = ratio.filter(|r| r.is_finite());
        }
    }
}
