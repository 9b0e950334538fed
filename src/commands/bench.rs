//! `rgraph bench`: every pipeline on every scene, measured: GPU time per pass and frame,
//! memory, shading work, image error against a reference; written as results.json,
//! results.md, charts and images.
//!
//! A row that cannot be measured becomes an error row naming its scene and pipeline and
//! the rest go on; the command fails (exit 1) only when no row could be measured.

mod candidates;
mod charts;
mod edge_pixels;
mod error;
mod figures;
mod image_error;
mod images;
mod machine;
mod measure;
mod memory;
mod particle_table;
mod particle_work;
mod progress;
mod reference;
mod results;
mod scene;
mod specialisation;
mod stats;
mod surfaces;
mod sweep;
mod table;
mod work;

use std::path::{Path, PathBuf};

use graph_core::gpu::AdapterChoice;

use super::{write_atomically, CommandError};
use crate::cli::BenchArgs;
use crate::frame::Session;
use error::BenchError;
use machine::{Adapter, Machine};
use measure::Setup;
use progress::Progress;
use reference::Reference;
use results::{Results, SCHEMA};
use scene::bench_scene;
use sweep::Step;

/// The pipeline every frame time is compared with.
const BASELINE: &str = "deferred_noaa";

pub fn run(args: &BenchArgs) -> Result<(), CommandError> {
    let json = bench(args)?;
    println!("{}", json.display());
    Ok(())
}

/// Measures, writes the results, and returns the path of results.json.
fn bench(args: &BenchArgs) -> Result<PathBuf, BenchError> {
    let out = &args.out_dir;
    std::fs::create_dir_all(out).map_err(|e| BenchError::OutDir {
        path: out.clone(),
        reason: e.to_string(),
    })?;
    // Taken before measuring: the commit and time the run started from.
    let (git_commit, timestamp) = (machine::git_commit(), machine::timestamp());
    let scenes = candidates::scenes(&args.scenes);
    let (pipelines, mut notes) = candidates::pipelines(&args.pipelines);
    let pipelines = match args.samples {
        Some(samples) => candidates::at_samples(pipelines, samples, &mut notes),
        None => pipelines,
    };
    let pipelines = candidates::with_params(pipelines, &args.params, &mut notes);
    let session = Session::open(&AdapterChoice::resolve(args.adapter.as_deref()))
        .map_err(BenchError::Device)?;
    let size = (args.width, args.height);
    let steps = sweep::steps(args.sweep, scenes, pipelines, size, &mut notes);
    // Sweeps measure cost only: a reference per sweep value would dominate the run.
    let reference = match (args.sweep, args.no_reference) {
        (None, false) => Reference::choose(args, &mut notes),
        (None, true) => {
            notes.push("--no-reference: image error is not measured".into());
            None
        }
        (Some(_), _) => None,
    };

    let mut results = Results {
        schema: SCHEMA,
        command: std::env::args().collect::<Vec<_>>().join(" "),
        machine: Machine::this(),
        adapter: Adapter::of(&session.gpu),
        git_commit,
        timestamp,
        resolution: [args.width, args.height],
        sweep: args.sweep,
        frames: args.frames,
        warmup: args.warmup,
        reference,
        notes,
        scenes: Vec::new(),
        rows: Vec::new(),
    };
    measure(&session, args, &steps, &mut results)?;
    let json_path = write_results(&results, out)?;
    eprintln!("{}", table::markdown(&results));
    if results.rows.iter().all(|r| r.figures.is_none()) {
        return Err(BenchError::NothingMeasured {
            rows: results.rows.len(),
            results: json_path,
        });
    }
    Ok(json_path)
}

/// Every step's scenes, with a progress bar over all their items, into `results`: the rows,
/// and each scene's summary outside sweeps. After each scene the results so far are
/// written, with a note saying how many scenes are missing, so a run stopped part way
/// (a machine lent for minutes) keeps what it measured.
fn measure(
    session: &Session,
    args: &BenchArgs,
    steps: &[Step],
    results: &mut Results,
) -> Result<(), BenchError> {
    let reference = results.reference.clone();
    let extra = |s: &Step| usize::from(reference.is_some()) + usize::from(s.point.is_none());
    // The reference and the unique-surface count are items of their own.
    let items = steps
        .iter()
        .map(|s| s.scenes.len() * (s.pipelines.len() + extra(s)))
        .sum();
    let scene_count: usize = steps.iter().map(|s| s.scenes.len()).sum();
    let mut progress = Progress::new(items);
    let mut done = 0;
    for step in steps {
        let setup = Setup {
            session,
            size: step.size,
            frames: args.frames,
            warmup: args.warmup,
            assets: args.assets.policy(),
            lighting: args.assets.lights,
        };
        // Images only outside sweeps, where one folder per scene is unambiguous.
        let images = step.point.is_none().then_some(args.out_dir.as_path());
        for scene in &step.scenes {
            let (scene_rows, summary) = bench_scene(
                &setup,
                scene,
                &step.pipelines,
                reference.as_ref(),
                images,
                &mut progress,
            )?;
            results.rows.extend(scene_rows.into_iter().map(|mut row| {
                row.sweep = step.point.clone();
                row
            }));
            if images.is_some() {
                results.scenes.push(summary);
            }
            results::ratios_to_baseline(&mut results.rows, BASELINE);
            done += 1;
            if done < scene_count {
                results.notes.push(format!(
                    "partial: {done} of {scene_count} scenes measured (the run was stopped \
                     before the rest, or is still running)"
                ));
                write_results(results, &args.out_dir)?;
                results.notes.pop();
            }
        }
    }
    Ok(())
}

/// results.json, results.md and the charts; returns the JSON's path.
fn write_results(results: &Results, out: &Path) -> Result<PathBuf, BenchError> {
    let json_path = out.join("results.json");
    // Plain structs of numbers and strings: serializing them cannot fail.
    let json = serde_json::to_string_pretty(results).expect("results serialize");
    write(&json_path, json.as_bytes())?;
    write(&out.join("results.md"), table::markdown(results).as_bytes())?;
    charts::write_all(results, out)?;
    Ok(json_path)
}

fn write(path: &Path, bytes: &[u8]) -> Result<(), BenchError> {
    write_atomically(path, bytes).map_err(|e| BenchError::Write {
        path: path.to_path_buf(),
        reason: e.to_string(),
    })
}
