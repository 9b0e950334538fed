//! `rgraph bench --motion orbit:DEG`: error over time. Each scene is drawn as a short
//! sequence by every pipeline and by the reference, frame by frame: 16 still frames (a
//! temporal filter's history fills), then `--motion-frames` frames with the camera
//! orbiting DEG degrees in all about the scene's centre and one object moving sideways (1%
//! of the scene's size a frame): the scene's first mesh smaller than a quarter of it
//! ([`moving_mesh`]), not a ground plane, whose shading (the shadows on it, its lights'
//! falloff) would stay where it was while its motion vectors said it moved. Per pipeline: the
//! GPU time of the sequence's last frame, the still FLIP (the last still frame against the
//! reference's), the sequence FLIP (the mean over the moving frames of each frame's FLIP
//! against the reference's same frame), and the instability: per pixel and channel, how
//! much more the pipeline's image changed from the frame before than the reference's did,
//! `max(0, |P_i - P_i-1| - |R_i - R_i-1|)`, averaged over the moving frames, in 1/255:
//! flicker (a jittered edge that the image does not settle) and ghosting (a change that
//! lags or smears) both count, a change the scene makes does not.
//!
//! The times are the still bench's (rounds.rs, timing.rs): after the sequence, with the
//! camera and objects held where its last frame put them and each pipeline's temporal
//! passes going on from the history the sequence left, the pipelines are timed together
//! in `--rounds` interleaved rounds of `--frames` frames after `--warmup` frames: the
//! median of the round medians, p10–p90, the spread and its flag, and each pass's time.
//! (A median of single frames each read back before the next, as this bench measured
//! before, disagreed with the still bench's rounds by up to 2.8 times on an H100.)
//!
//! Written as motion.md (the table), motion.json (with each frame's FLIP) and motion.png
//! (the FLIP frame by frame, src/commands/bench/charts/motion.rs) in --out-dir.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use image::RgbaImage;
use rgraph_core::file::GraphParams;
use rgraph_passes::{FrameInputs, Host, Overrides};
use rgraph_scene::glam::{DMat4, DVec3};
use serde::Serialize;

use super::charts::{self, Series};
use super::error::BenchError;
use super::flag::SPREAD_LIMIT;
use super::image_error::flip_mean;
use super::measure::Setup;
use super::progress::Progress;
use super::rounds::{interleave, RoundLog, Timed};
use super::table;
use super::timing::Times;
use crate::cli::BenchArgs;
use crate::commands::write_atomically;
use crate::frame::{host, FrameError, Pipeline, Prepared, Specialise};

/// Still frames before the moving ones: one cycle of the TAA jitter.
const STILL_FRAMES: u32 = 16;
/// The moving mesh moves this share of the scene's bounds diagonal each moving frame.
const MESH_STEP: f64 = 0.01;
/// The largest share of the scene's bounds diagonal the moving mesh's may be.
const MOVING_MESH_SIZE: f64 = 0.25;

/// What a motion bench measures without `--pipeline`: no AA, FXAA, MSAA 4x, TAA and MSAA
/// 4x + TAA, all on the default (visibility buffer) path.
const DEFAULT_PIPELINES: [(&str, &str, Option<u32>); 5] = [
    ("no AA", "pipelines/visibility_noaa.ron", None),
    ("FXAA", "pipelines/visibility_msaa_4x_fxaa.ron", Some(1)),
    ("MSAA 4x", "pipelines/visibility_msaa_4x.ron", None),
    ("TAA", "pipelines/taa.ron", None),
    ("MSAA 4x + TAA", "pipelines/msaa_4x_taa.ron", None),
];

/// One pipeline's figures on one scene.
#[derive(Debug, Serialize)]
pub struct MotionRow {
    pub scene: String,
    pub pipeline: String,
    pub file: PathBuf,
    /// The sequence's last frame timed in interleaved rounds, as results.json's rows.
    #[serde(flatten)]
    pub times: Times,
    pub still_flip: f64,
    pub sequence_flip: f64,
    /// In 1/255 per channel.
    pub instability: f64,
    /// The FLIP of each frame against the reference's: the last still frame, then the
    /// moving ones.
    pub flips: Vec<f64>,
}

#[derive(Serialize)]
struct MotionResults<'a> {
    command: String,
    adapter: String,
    resolution: [u32; 2],
    orbit_degrees: f64,
    still_frames: u32,
    moving_frames: u32,
    /// Measured frames of each pipeline per round, rounds and warmup frames.
    frames: u32,
    rounds: u32,
    warmup: u32,
    spread_limit: f64,
    rows: &'a [MotionRow],
    round_log: &'a [RoundLog],
}

/// What one pipeline of the sequence measured: its name in the table, its file, what it
/// drew last and its figures so far.
struct Drawn {
    name: String,
    file: PathBuf,
    last: Option<RgbaImage>,
    flips: Vec<f64>,
    unstable: Vec<f64>,
    still_flip: f64,
}

/// Runs the motion bench, timing as `setup` says, and returns the path of motion.json.
pub fn bench(args: &BenchArgs, degrees: f64, setup: &Setup) -> Result<PathBuf, BenchError> {
    let scenes = match args.scenes.is_empty() {
        true => vec!["builtin:spheres".to_owned()],
        false => args.scenes.clone(),
    };
    let pipelines: Vec<(String, PathBuf, GraphParams)> = match args.pipelines.is_empty() {
        true => DEFAULT_PIPELINES
            .iter()
            .map(|(name, file, msaa)| {
                let params =
                    msaa.map_or_else(GraphParams::new, |m| GraphParams::new().with("msaa", m));
                (name.to_string(), PathBuf::from(file), params)
            })
            .collect(),
        false => args
            .pipelines
            .iter()
            .map(|p| (stem(p), p.clone(), GraphParams::new()))
            .collect(),
    };
    let frames = args.motion_frames;
    let mut rows = Vec::new();
    let mut log = Vec::new();
    // Per scene its sequence, warmup and rounds (rounds.rs adds further memory groups').
    let mut progress = Progress::new(scenes.len() * (2 + args.rounds as usize));
    for spec in &scenes {
        progress.item(format!("{spec}: the sequence"));
        let scene = args
            .assets
            .load(spec)
            .map_err(|e| failed(spec, e.to_string()))?;
        let overrides = Overrides {
            shadows: args.shadows.settings(),
            ..Overrides::default()
        };
        let host = host(Arc::new(scene), overrides);
        let load = |file: &Path, params: &GraphParams| {
            let pipeline =
                Pipeline::load(file, host.clone(), &["color"], Specialise::ToScene, params)?;
            setup.session.prepare(pipeline, setup.size)
        };
        let mut reference = load(&args.reference, &GraphParams::new())
            .map_err(|e| failed(spec, format!("the reference: {e}")))?;
        let (mut drawn, mut plans) = (Vec::new(), Vec::new());
        for (name, file, params) in &pipelines {
            plans.push(load(file, params).map_err(|e| failed(spec, format!("{name}: {e}")))?);
            drawn.push(Drawn {
                name: name.clone(),
                file: file.clone(),
                last: None,
                flips: Vec::new(),
                unstable: Vec::new(),
                still_flip: 0.0,
            });
        }
        let start = FrameInputs::clone(&host.frame());
        let moving = moving_mesh(&host.scene);
        let mut reference_last = None;
        for index in 0..STILL_FRAMES + frames {
            let moving_frame = index.saturating_sub(STILL_FRAMES - 1);
            let step = degrees / f64::from(frames.max(1));
            let inputs = posed(&host, &start, (moving_frame, moving), step);
            host.set_frame(inputs)
                .map_err(|e| failed(spec, e.to_string()))?;
            let measured = index + 1 >= STILL_FRAMES;
            let reference_image = match measured {
                true => Some(
                    frame(&mut reference)
                        .map_err(|e| failed(spec, format!("the reference: {e}")))?,
                ),
                false => None,
            };
            let images = (plans.iter_mut().zip(&drawn))
                .map(|(plan, d)| frame(plan).map_err(|e| failed(spec, format!("{}: {e}", d.name))))
                .collect::<Result<Vec<_>, _>>()?;
            for (d, image) in drawn.iter_mut().zip(images) {
                if let Some(reference_image) = &reference_image {
                    let flip = flip_mean(reference_image, &image);
                    match index + 1 == STILL_FRAMES {
                        true => d.still_flip = flip,
                        false => {
                            d.flips.push(flip);
                            if let (Some(last), Some(reference_last)) = (&d.last, &reference_last) {
                                d.unstable.push(instability(
                                    (last, &image),
                                    (reference_last, reference_image),
                                ));
                            }
                        }
                    }
                }
                d.last = Some(image);
            }
            if reference_image.is_some() {
                reference_last = reference_image;
            }
        }
        // The last frame timed as the still bench times, the reference's memory given
        // back first.
        drop(reference);
        let timed = (plans.into_iter().zip(&drawn).enumerate())
            .map(|(index, (prepared, d))| Timed {
                name: d.name.clone(),
                prepared,
                tag: index,
            })
            .collect();
        let mut times: Vec<Option<Result<Times, FrameError>>> =
            drawn.iter().map(|_| None).collect();
        let closed = interleave(
            setup,
            spec,
            timed,
            &mut progress,
            &mut log,
            |plan, timing| (plan.tag, timing.map(|t| t.times())),
        );
        for (index, timing) in closed {
            times[index] = Some(timing);
        }
        for (d, timing) in drawn.into_iter().zip(times) {
            // interleave closes every plan it is given.
            let times = timing
                .expect("every plan was timed")
                .map_err(|e| failed(spec, format!("{}, timed: {e}", d.name)))?;
            let row = MotionRow {
                scene: spec.clone(),
                pipeline: d.name,
                file: d.file,
                times,
                still_flip: d.still_flip,
                sequence_flip: mean(&d.flips),
                instability: mean(&d.unstable),
                flips: [d.still_flip].into_iter().chain(d.flips).collect(),
            };
            progress.note(table_line(&row));
            rows.push(row);
        }
    }
    write(args, degrees, setup, &rows, &log)
}

/// The mesh the bench moves: the first whose world bounds' diagonal is at most
/// `MOVING_MESH_SIZE` of the scene's (so not a ground plane), or none.
fn moving_mesh(scene: &rgraph_scene::Scene) -> Option<usize> {
    let size = (scene.bounds.max - scene.bounds.min).length();
    scene.meshes.iter().position(|mesh| {
        mesh.world_bounds()
            .is_some_and(|b| (b.max - b.min).length() <= MOVING_MESH_SIZE * size)
    })
}

/// The `index`-th moving frame's inputs (0: the start): the camera orbited by `step`
/// degrees a frame about the scene's centre, mesh `mesh` moved sideways.
fn posed(
    host: &Host,
    start: &FrameInputs,
    (index, mesh): (u32, Option<usize>),
    step: f64,
) -> FrameInputs {
    let scene = &host.scene;
    let index = f64::from(index);
    let mut inputs = FrameInputs {
        camera: start
            .camera
            .orbited(scene.bounds.center(), (step * index).to_radians()),
        ..start.clone()
    };
    if let Some(moved) = mesh.and_then(|m| inputs.transforms.get_mut(m)) {
        let size = (scene.bounds.max - scene.bounds.min).length();
        let shift = DVec3::new(MESH_STEP * size * index, 0.0, 0.0);
        *moved = DMat4::from_translation(shift) * *moved;
    }
    inputs
}

/// Runs one frame of `prepared` and reads its "color" back.
fn frame(prepared: &mut Prepared<'_>) -> Result<RgbaImage, FrameError> {
    prepared.run(1)?;
    prepared.read("color")
}

/// How much more the pipeline's image changed between two frames than the reference's,
/// per pixel and channel, in 1/255: `max(0, |P1 - P0| - |R1 - R0|)`, averaged.
pub fn instability(
    (before, now): (&RgbaImage, &RgbaImage),
    (reference_before, reference_now): (&RgbaImage, &RgbaImage),
) -> f64 {
    let change =
        |a: &image::Rgba<u8>, b: &image::Rgba<u8>, c: usize| f64::from(a.0[c].abs_diff(b.0[c]));
    let pixels = before
        .pixels()
        .zip(now.pixels())
        .zip(reference_before.pixels().zip(reference_now.pixels()));
    let (mut sum, mut count) = (0.0, 0usize);
    for ((p0, p1), (r0, r1)) in pixels {
        for c in 0..3 {
            sum += (change(p0, p1, c) - change(r0, r1, c)).max(0.0);
            count += 1;
        }
    }
    sum / count.max(1) as f64
}

fn mean(values: &[f64]) -> f64 {
    values.iter().sum::<f64>() / values.len().max(1) as f64
}

fn stem(path: &Path) -> String {
    path.file_stem().map_or_else(
        || path.display().to_string(),
        |s| s.to_string_lossy().into_owned(),
    )
}

fn failed(scene: &str, why: String) -> BenchError {
    BenchError::Motion {
        scene: scene.to_owned(),
        why,
    }
}

const HEADER: &str = "| scene | pipeline | GPU ms | p10–p90 | spread | still FLIP | \
                      sequence FLIP | instability (1/255) |\n\
                      | --- | --- | --: | --: | --: | --: | --: | --: |";

fn table_line(row: &MotionRow) -> String {
    let times = &row.times;
    format!(
        "| {} | {} | {} | {:.4} | {:.4} | {:.3} |",
        row.scene,
        row.pipeline,
        table::time_cells(times.gpu_frame_ms.as_ref(), times.flag.is_some()).join(" | "),
        row.still_flip,
        row.sequence_flip,
        row.instability
    )
}

/// A row's name under the table: its scene and pipeline.
fn row_name(row: &MotionRow) -> String {
    format!("{}: {}", row.scene, row.pipeline)
}

/// motion.md and motion.json in --out-dir; returns the JSON's path.
fn write(
    args: &BenchArgs,
    degrees: f64,
    setup: &Setup,
    rows: &[MotionRow],
    log: &[RoundLog],
) -> Result<PathBuf, BenchError> {
    let out = &args.out_dir;
    let command = std::env::args().collect::<Vec<_>>().join(" ");
    let adapter = setup.session.profile.name.clone();
    let lines: Vec<String> = rows.iter().map(table_line).collect();
    let mut scenes: Vec<&str> = rows.iter().map(|r| r.scene.as_str()).collect();
    scenes.dedup();
    let rounds: String = scenes
        .iter()
        .map(|s| table::rounds_line(log, s, "motion.json"))
        .collect();
    let flags = (rows.iter()).filter_map(|r| Some((row_name(r), r.times.flag.as_ref()?)));
    let passes = table::pass_table(rows.iter().map(|r| (row_name(r), &r.times.passes[..])));
    let markdown = format!(
        "# Error over time\n\n`{command}`\n\nAdapter {adapter}, {}x{}: {STILL_FRAMES} still frames, \
         then {} frames with the camera orbiting {degrees} degrees and the first mesh \
         smaller than a quarter of the scene moving sideways. Still FLIP: the last still frame; sequence FLIP: the mean over the moving \
         frames; instability: how much more each frame changed than the reference's did \
         (src/commands/bench/motion.rs). GPU ms: the sequence's last frame (camera and \
         objects held there, temporal passes going on from their history), the pipelines \
         timed together in {} interleaved rounds of {} frames each after {} warmup frames{}, \
         as `rgraph bench` times them: the median of the round medians, p10–p90 of the \
         round medians, spread (p90 − p10) / median; a time whose spread exceeds {} is \
         flagged {}.\n\n{rounds}{HEADER}\n{}\n{}{passes}\n![FLIP per frame](motion.png)\n",
        args.width,
        args.height,
        args.motion_frames,
        setup.rounds,
        setup.frames,
        setup.warmup,
        table::warmup_span(setup.warmup),
        table::percent(SPREAD_LIMIT),
        table::FLAG,
        lines.join("\n"),
        table::flagged(flags, SPREAD_LIMIT),
    );
    let results = MotionResults {
        command,
        adapter,
        resolution: [args.width, args.height],
        orbit_degrees: degrees,
        still_frames: STILL_FRAMES,
        moving_frames: args.motion_frames,
        frames: setup.frames,
        rounds: setup.rounds,
        warmup: setup.warmup,
        spread_limit: SPREAD_LIMIT,
        rows,
        round_log: log,
    };
    let json = serde_json::to_string_pretty(&results).unwrap_or_default();
    let written = |path: PathBuf, bytes: &[u8]| {
        write_atomically(&path, bytes).map_err(|e| BenchError::Write {
            path: path.clone(),
            reason: e.to_string(),
        })?;
        Ok::<_, BenchError>(path)
    };
    written(out.join("motion.md"), markdown.as_bytes())?;
    let series: Vec<Series<'_>> = rows
        .iter()
        .map(|r| Series {
            scene: &r.scene,
            pipeline: &r.pipeline,
            flips: r.flips.clone(),
        })
        .collect();
    // The adapter's name up to its driver's, which would not fit one panel's width.
    let adapter = results.adapter.split(" [").next().unwrap_or_default();
    let title = format!(
        "FLIP per frame: {adapter}, {}x{}, orbit {degrees} degrees over {} frames",
        args.width, args.height, args.motion_frames
    );
    charts::write_motion(&series, &title, out)?;
    written(out.join("motion.json"), json.as_bytes())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grey(value: u8) -> RgbaImage {
        RgbaImage::from_pixel(4, 4, image::Rgba([value, value, value, 255]))
    }

    /// A pipeline that flickers on purpose (alternating frames) ranks last; one that
    /// follows the reference's own change has none; a change the scene makes is not
    /// counted.
    #[test]
    fn instability_counts_only_change_beyond_the_references() {
        let reference = [grey(100), grey(120), grey(140), grey(160)];
        let follows = reference.clone();
        let lags = [grey(100), grey(110), grey(125), grey(145)];
        let flickers = [grey(100), grey(140), grey(120), grey(180)];
        let score = |frames: &[RgbaImage; 4]| {
            let per_frame: Vec<f64> = (1..4)
                .map(|i| {
                    instability(
                        (&frames[i - 1], &frames[i]),
                        (&reference[i - 1], &reference[i]),
                    )
                })
                .collect();
            mean(&per_frame)
        };
        let (follows, lags, flickers) = (score(&follows), score(&lags), score(&flickers));
        assert_eq!(follows, 0.0);
        assert!(lags < flickers, "lags {lags}, flickers {flickers}");
        assert_eq!(flickers, (20.0 + 0.0 + 40.0) / 3.0);
    }
}
