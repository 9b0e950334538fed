//! Everything a bench measured, as written to results.json (and read by the table and the
//! charts). Figures that could not be measured are `null`, with the reason nearby.

use rgraph_scene::Scene;
use serde::Serialize;

use super::clocks::ClockSource;
use super::edge_pixels::EdgePixels;
use super::figures::Figures;
use super::machine::{Adapter, Machine};
use super::reference::Reference;
use super::rounds::RoundLog;
use super::surfaces::UniqueSurfaces;
use super::sweep::SweepPoint;
use crate::cli::Sweep;

/// Bumped when a field changes meaning or moves: 3 when times became medians of
/// interleaved rounds' medians and `frames` the frames of a round.
pub const SCHEMA: u32 = 3;

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
    /// Wall-clock seconds the run took (so far, in a partial file).
    pub elapsed_s: f64,
    /// The size asked for (a resolution sweep replaces it: see each row's `sweep`).
    pub resolution: [u32; 2],
    /// What `--sweep` varied, if anything.
    pub sweep: Option<Sweep>,
    /// Measured frames of each pipeline per round.
    pub frames: u32,
    /// Interleaved rounds per scene (and memory group).
    pub rounds: u32,
    /// Warmup frames of each pipeline before round 1.
    pub warmup: u32,
    /// Rows whose `gpu_frame_ms.spread` exceeds this are flagged.
    pub spread_limit: f64,
    /// The most pooled memory the plans timed together in one round may ask for.
    pub group_memory_bytes: u64,
    /// Whether the GPU's clocks are sampled, how, or why not.
    pub gpu_clocks: ClockSource,
    /// What errors are measured against; `null` when nothing could be.
    pub reference: Option<Reference>,
    /// Things the reader should know: skipped files, substitutes, unmeasured figures.
    pub notes: Vec<String>,
    /// Per scene: its size, its images folder and its edge pixels (in a sweep, each value's
    /// scene once).
    pub scenes: Vec<SceneSummary>,
    /// One per scene and pipeline (and sweep value), error rows included.
    pub rows: Vec<Row>,
    /// Every round in the order it ran: its scene, the plans in the order they ran, and
    /// the GPU's clocks meanwhile.
    pub round_log: Vec<RoundLog>,
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

/// What a scene's rows share: where its images are, how its edge pixels were found and
/// the least shading it needs.
#[derive(Debug, Serialize)]
pub struct SceneSummary {
    pub scene: String,
    /// What the scene holds; `null` when it could not be loaded.
    pub size: Option<SceneSize>,
    /// The folder of its images; empty in sweeps, which write none.
    pub images: String,
    /// The pixels edge errors are measured on; `null` without a reference.
    pub edge_pixels: Option<EdgePixels>,
    /// Why the reference could not be rendered, when it could not.
    pub reference_error: Option<String>,
    /// The lower bound of shading work; `null` in sweeps or when it failed.
    pub unique_surfaces: Option<UniqueSurfaces>,
    /// Why the bound could not be measured, when it could not.
    pub unique_surfaces_error: Option<String>,
}

/// How big a scene is: what a sweep over triangles, meshes or lights varies, and the
/// geometry every pipeline uploads before its first frame.
#[derive(Clone, Debug, Serialize)]
pub struct SceneSize {
    pub triangles: usize,
    pub meshes: usize,
    /// Point, spot and directional lights.
    pub lights: usize,
    /// Vertices and indices as uploaded: what the plan's memory figures leave out.
    pub geometry_bytes: u64,
}

impl SceneSize {
    pub fn of(scene: &Scene) -> SceneSize {
        let stats = scene.stats();
        SceneSize {
            triangles: stats.triangles,
            meshes: stats.meshes,
            lights: stats.point_lights + stats.spot_lights + stats.directional_lights,
            geometry_bytes: stats.geometry_bytes(),
        }
    }
}
