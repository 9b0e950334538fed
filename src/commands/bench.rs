//! `rgraph bench`: every pipeline on every scene, measured: GPU time per pass and frame,
//! memory, shading work, image error against a reference; written as results.json,
//! results.md, charts and images. A scene's pipelines are timed in interleaved rounds
//! (rounds.rs), each figure the median of its round medians (stats.rs), and a row whose
//! rounds disagree by more than 5% is flagged with what the bench knows of why (flag.rs,
//! with the GPU's clocks from clocks.rs).
//!
//! A row that cannot be measured becomes an error row naming its scene and pipeline and
//! the rest go on; the command fails (exit 1) only when no row could be measured.

mod candidates;
mod charts;
mod clocks;
mod edge_pixels;
mod error;
mod figures;
mod flag;
pub mod image_error;
mod images;
mod machine;
mod measure;
mod memory;
mod motion;
mod particle_table;
mod particle_work;
mod plan_page;
mod progress;
mod reference;
mod results;
mod rounds;
mod scene;
mod specialisation;
mod stats;
mod surfaces;
mod sweep;
mod table;
mod timing;
mod work;

use std::path::{Path, PathBuf};
use std::time::Instant;

use rgraph_core::gpu::AdapterChoice;
use rgraph_passes::Shadows;

use super::{write_atomically, CommandError};
use crate::cli::BenchArgs;
use crate::frame::Session;
use clocks::ClockSource;
use error::BenchError;
use flag::SPREAD_LIMIT;
use machine::{Adapter, Machine};
use measure::Setup;
use progress::Progress;
use reference::Reference;
use results::{Results, SCHEMA};
use scene::bench_scene;
use sweep::Step;

/// The pipeline every frame time is compared with.
const BASELINE: &str = "deferred_noaa";
/// The share of the GPU's memory (as `nvidia-smi` reports it) one interleaved group's
/// plans may ask for without `--group-memory`: room left for the scene's uploads and
/// the buffers passes keep, which the plans do not count.
const GROUP_SHARE: f64 = 0.6;
/// The group budget where the GPU's memory is not reported (lavapipe, other vendors).
const GROUP_DEFAULT_BYTES: u64 = 4 << 30;

pub fn run(args: &BenchArgs) -> Result<(), CommandError> {
    let json = bench(args)?;
    println!("{}", json.display());
    Ok(())
}

/// Measures, writes the results, and returns the path of results.json.
fn bench(args: &BenchArgs) -> Result<PathBuf, BenchError> {
    let started = Instant::now();
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
    let pipelines = candidates::drawing_shadow_maps(pipelines, &args.params, &mut notes);
    let session = Session::open(&AdapterChoice::resolve(args.adapter.as_deref()))
        .map_err(BenchError::Device)?;
    let size = (args.width, args.height);
    let gpu_clocks = ClockSource::for_gpu(&session.gpu);
    let group_memory_bytes = match (args.group_memory, gpu_clocks.memory_total_bytes) {
        (Some(mib), _) => mib << 20,
        (None, Some(total)) => (total as f64 * GROUP_SHARE) as u64,
        (None, None) => GROUP_DEFAULT_BYTES,
    };
    let fake_slow_round = std::env::var(rounds::FAKE_SLOW_ROUND)
        .ok()
        .and_then(|v| v.parse().ok());
    // What every timing of the run shares, for one size and sweep value.
    let setup = |size: (u32, u32), sweep: Option<String>| Setup {
        session: &session,
        size,
        frames: args.frames,
        rounds: args.rounds,
        warmup: args.warmup,
        group_bytes: group_memory_bytes,
        clocks: &gpu_clocks,
        fake_slow_round,
        sweep,
        assets: args.assets.policy(),
        lighting: args.assets.lights,
        shadows: args.shadows.settings(),
    };
    if let Some(degrees) = args.motion {
        return motion::bench(args, degrees, &setup(size, None));
    }
    let steps = sweep::steps(
        args.sweep,
        args.sweep_max,
        scenes,
        pipelines,
        size,
        &mut notes,
    );
    if let Some(round) = fake_slow_round {
        notes.push(format!(
            "{}={round}: a test hook made round {round}'s GPU times three times as long; \
             these figures are not measurements",
            rounds::FAKE_SLOW_ROUND
        ));
    }
    let shadows = args.shadows.settings();
    if shadows != Shadows::default() {
        notes.push(format!(
            "shadows: {}, at most {} shadowed lights (--shadows, --shadowed-lights)",
            shadows.filter.name(),
            shadows.lights
        ));
    }
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
        elapsed_s: 0.0,
        sweep: args.sweep,
        frames: args.frames,
        rounds: args.rounds,
        warmup: args.warmup,
        spread_limit: SPREAD_LIMIT,
        group_memory_bytes,
        gpu_clocks: gpu_clocks.clone(),
        reference,
        notes,
        scenes: Vec::new(),
        rows: Vec::new(),
        round_log: Vec::new(),
    };
    let step_setup = |step: &Step| setup(step.size, step.point.as_ref().map(|p| p.label.clone()));
    measure(args, &steps, step_setup, started, &mut results)?;
    results.elapsed_s = started.elapsed().as_secs_f64();
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
/// the rounds, and each scene's summary outside sweeps. After each scene the results so
/// far are written, with a note saying how many scenes are missing, so a run stopped part
/// way (a machine lent for minutes) keeps what it measured.
fn measure<'a>(
    args: &BenchArgs,
    steps: &[Step],
    setup: impl Fn(&Step) -> Setup<'a>,
    started: Instant,
    results: &mut Results,
) -> Result<(), BenchError> {
    let reference = results.reference.clone();
    // The reference and the unique-surface count are items of their own; each pipeline
    // is compiled, then finished after the rounds; a scene's warmup and rounds are
    // counted for one memory group (rounds.rs adds the others').
    let extra = |s: &Step| {
        usize::from(reference.is_some()) + usize::from(s.point.is_none()) + 1 + args.rounds as usize
    };
    let items = steps
        .iter()
        .map(|s| s.scenes.len() * (2 * s.pipelines.len() + extra(s)))
        .sum();
    let scene_count: usize = steps.iter().map(|s| s.scenes.len()).sum();
    let mut progress = Progress::new(items);
    let mut done = 0;
    for step in steps {
        let setup = setup(step);
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
                &mut results.round_log,
            )?;
            results.rows.extend(scene_rows.into_iter().map(|mut row| {
                row.sweep = step.point.clone();
                row
            }));
            // A resolution or samples sweep measures one scene at every step: summarised once.
            if !results.scenes.iter().any(|s| s.scene == summary.scene) {
                results.scenes.push(summary);
            }
            results::ratios_to_baseline(&mut results.rows, BASELINE);
            done += 1;
            if done < scene_count {
                results.notes.push(format!(
                    "partial: {done} of {scene_count} scenes measured (the run was stopped \
                     before the rest, or is still running)"
                ));
                results.elapsed_s = started.elapsed().as_secs_f64();
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
