//! `rgraph bench`: every pipeline on every scene, measured: GPU time per pass and frame,
//! memory, shading work, image error against a reference; written as results.json,
//! results.md, charts and images.
//!
//! A row that cannot be measured becomes an error row naming its scene and pipeline and
//! the rest go on; the command fails (exit 1) only when no row could be measured.

mod candidates;
mod error;
mod machine;
mod measure;
mod memory;
mod progress;
mod results;
mod stats;
mod table;
mod work;

use std::path::Path;
use std::sync::Arc;

use graph_core::gpu::AdapterChoice;
use passes_deferred_msaa::scene::Scene;
use passes_deferred_msaa::Overrides;

use super::{write_atomically, CommandError};
use crate::cli::BenchArgs;
use crate::frame::{host, Session};
use candidates::Candidate;
use error::{BenchError, RowError};
use machine::{Adapter, Machine};
use measure::Setup;
use progress::Progress;
use results::{Results, Row, SCHEMA};

/// The pipeline every frame time is compared with.
const BASELINE: &str = "deferred_noaa";

pub fn run(args: &BenchArgs) -> Result<(), CommandError> {
    let json = bench(args)?;
    println!("{}", json.display());
    Ok(())
}

/// Measures, writes the results, and returns the path of results.json.
fn bench(args: &BenchArgs) -> Result<std::path::PathBuf, BenchError> {
    let out = &args.out_dir;
    std::fs::create_dir_all(out).map_err(|e| BenchError::OutDir {
        path: out.clone(),
        reason: e.to_string(),
    })?;
    let scenes = candidates::scenes(&args.scenes);
    let (pipelines, mut notes) = candidates::pipelines(&args.pipelines);
    let session = Session::open(&AdapterChoice::resolve(args.adapter.as_deref()))
        .map_err(BenchError::Device)?;
    let setup = Setup {
        session: &session,
        size: (args.width, args.height),
        frames: args.frames,
        warmup: args.warmup,
    };

    let mut progress = Progress::new(scenes.len() * pipelines.len());
    let mut rows = Vec::new();
    for scene in &scenes {
        rows.extend(bench_scene(&setup, scene, &pipelines, &mut progress));
    }
    drop(progress);
    ratios_to_baseline(&mut rows);
    notes.push(
        "unique_surface_bound (one shading per distinct surface in a pixel) is not measured: \
         it needs per-sample primitive identity, which no pipeline exports"
            .into(),
    );

    let results = Results {
        schema: SCHEMA,
        command: std::env::args().collect::<Vec<_>>().join(" "),
        machine: Machine::this(),
        adapter: Adapter::of(&session.gpu),
        git_commit: machine::git_commit(),
        timestamp: machine::timestamp(),
        resolution: [args.width, args.height],
        frames: args.frames,
        warmup: args.warmup,
        notes,
        rows,
    };
    let json_path = out.join("results.json");
    let json = serde_json::to_string_pretty(&results).expect("results serialize");
    write(&json_path, json.as_bytes())?;
    let table = table::markdown(&results);
    write(&out.join("results.md"), table.as_bytes())?;
    eprintln!("{table}");
    if results.rows.iter().all(|r| r.figures.is_none()) {
        return Err(BenchError::NothingMeasured {
            rows: results.rows.len(),
            results: json_path,
        });
    }
    Ok(json_path)
}

/// Every pipeline on one scene; a scene that fails to load makes every row an error.
fn bench_scene(
    setup: &Setup,
    spec: &str,
    pipelines: &[Candidate],
    progress: &mut Progress,
) -> Vec<Row> {
    let scene = match Scene::load(spec) {
        Ok(scene) => Arc::new(scene),
        Err(source) => {
            let message = RowError::Scene {
                scene: spec.to_string(),
                source,
            }
            .to_string();
            progress.note(format!("error: {message}"));
            // One row for the scene: no pipeline ran on it.
            return vec![Row::error(spec, "-", "", message)];
        }
    };
    let host = host(scene, Overrides::default());
    pipelines
        .iter()
        .map(|candidate| {
            progress.item(format!("{spec} {}", candidate.name));
            match setup.measure(candidate, &host) {
                Ok(measured) => Row::ok(spec, &candidate.name, &file(candidate), measured.figures),
                Err(source) => {
                    let message = RowError::Frame {
                        pipeline: candidate.name.clone(),
                        scene: spec.to_string(),
                        source,
                    }
                    .to_string();
                    progress.note(format!("error: {message}"));
                    Row::error(spec, &candidate.name, &file(candidate), message)
                }
            }
        })
        .collect()
}

/// Each measured row's median GPU frame time over the baseline's on the same scene.
fn ratios_to_baseline(rows: &mut [Row]) {
    let median = |row: &Row| {
        row.figures
            .as_ref()?
            .gpu_frame_ms
            .as_ref()
            .map(|s| s.median)
    };
    let baselines: Vec<(String, f64)> = rows
        .iter()
        .filter(|r| r.pipeline == BASELINE)
        .filter_map(|r| Some((r.scene.clone(), median(r)?)))
        .collect();
    for row in rows.iter_mut() {
        let base = baselines.iter().find(|(s, _)| *s == row.scene).map(|b| b.1);
        let ratio = base.zip(median(row)).map(|(b, m)| m / b);
        if let Some(figures) = &mut row.figures {
            figures.ratio_to_noaa = ratio.filter(|r| r.is_finite());
        }
    }
}

fn file(candidate: &Candidate) -> String {
    candidate.path.display().to_string()
}

fn write(path: &Path, bytes: &[u8]) -> Result<(), BenchError> {
    write_atomically(path, bytes).map_err(|e| BenchError::Write {
        path: path.to_path_buf(),
        reason: e.to_string(),
    })
}
