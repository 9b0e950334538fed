//! Timing a scene's pipelines in interleaved rounds: each round runs `--frames` frames of
//! every pipeline in turn (A B C, A B C, ...), so a GPU whose clocks drift, or that
//! something else slows for a while, shows as rounds that disagree instead of as
//! whichever pipeline ran then measured slow. Before round 1 each pipeline runs its warmup frames (its first
//! frame creates its pipelines and uploads the scene), then all of them take turns until
//! [`WARM_FOR`] has passed. Every round is logged with the order its pipelines ran in
//! and, where the platform reports them, the GPU's clocks while it ran.
//!
//! All pipelines of a round are alive at once. To bound the memory that takes, the
//! pipelines are split into consecutive groups whose plans' pooled memory (what
//! results.json's `memory.physical_bytes` counts, before any frame) stays within
//! `--group-memory`; each group is warmed, measured in its rounds and dropped before the
//! next one begins. A pipeline larger than the budget on its own is a group of its own.

use std::ops::Range;
use std::time::{Duration, Instant};

use rgraph_core::gpu::FrameReport;
use serde::Serialize;

use super::clocks::ClockSample;
use super::flag::Created;
use super::measure::Setup;
use super::memory::Memory;
use super::progress::Progress;
use super::timing::Timing;
use crate::frame::{FrameError, Prepared};

/// The least time the warmup runs when there is one: a GPU clocks down while the bench
/// works on the CPU between scenes (FLIP at 2160p takes seconds), and on the H200 frames of
/// a few milliseconds then took up to five times as long until its clocks came back,
/// which two warmup frames did not wait for.
const WARM_FOR: Duration = Duration::from_millis(500);

/// A test hook: `RGRAPH_BENCH_FAKE_SLOW_ROUND=N` makes round N's GPU times ten times as
/// long for every pipeline, as a GPU slowed for one round would measure, so that tests
/// can see a slow round flagged (by a margin no noise of a busy CPU adapter reaches:
/// three times was reached once, the test suite's other GPU tests sharing two cores).
/// The results' notes say when it was set.
pub const FAKE_SLOW_ROUND: &str = "RGRAPH_BENCH_FAKE_SLOW_ROUND";

/// One plan to time: its name in the round log, the plan, and what its owner needs to
/// find it again.
pub struct Timed<'s, T> {
    pub name: String,
    pub prepared: Prepared<'s>,
    pub tag: T,
}

/// One round in results.json's `round_log`.
#[derive(Clone, Debug, Serialize)]
pub struct RoundLog {
    pub scene: String,
    /// The sweep value, in a sweep.
    pub sweep: Option<String>,
    /// The memory group (from 1): pipelines of different groups never share a round.
    pub group: u32,
    /// From 1.
    pub round: u32,
    /// The plans whose frames ran in this round, in the order they ran (a plan whose
    /// frame failed is dropped from later rounds).
    pub order: Vec<String>,
    /// Sampled while the round ran; `null` where not reported.
    pub clocks: Option<ClockSample>,
}

/// A plan being timed.
struct Running<'s, T> {
    timed: Timed<'s, T>,
    timing: Timing,
    failed: Option<FrameError>,
}

/// Times `plans` on `scene` in interleaved rounds, group by group, appending each round
/// to `log`; `close` gets each plan, once its group is measured, with its timing or the
/// error that stopped it, and what it returns is kept in the order of `plans`.
pub fn interleave<'s, T, C>(
    setup: &Setup,
    scene: &str,
    plans: Vec<Timed<'s, T>>,
    progress: &mut Progress,
    log: &mut Vec<RoundLog>,
    mut close: impl FnMut(Timed<'s, T>, Result<Timing, FrameError>) -> C,
) -> Vec<C> {
    let sizes: Vec<u64> = plans
        .iter()
        .map(|t| Memory::of(t.prepared.plan(), &[]).allocated_bytes())
        .collect();
    let groups = groups(&sizes, setup.group_bytes);
    let count = groups.len();
    // One group was counted for the scene beforehand.
    progress.add(count.saturating_sub(1) * (1 + setup.rounds as usize));
    let mut plans = plans.into_iter();
    let mut closed = Vec::new();
    for (index, range) in groups.into_iter().enumerate() {
        let mut group: Vec<Running<T>> = plans
            .by_ref()
            .take(range.len())
            .map(|timed| Running {
                timed,
                timing: Timing {
                    rounds: Vec::new(),
                    created: Vec::new(),
                    clocks: Vec::new(),
                },
                failed: None,
            })
            .collect();
        // What the progress bar says of the group: "builtin:dense, 12 plans".
        let plans_text = match group.len() {
            1 => "1 plan".to_string(),
            n => format!("{n} plans"),
        };
        let what = match count {
            1 => format!("{scene}, {plans_text}"),
            _ => format!("{scene}, group {} of {count} ({plans_text})", index + 1),
        };
        progress.item(format!("{what}: warmup"));
        warm(setup, &mut group);
        for round in 1..=setup.rounds {
            progress.item(format!("{what}: round {round} of {}", setup.rounds));
            let (order, clocks) = run_round(setup, round, &mut group);
            log.push(RoundLog {
                scene: scene.to_string(),
                sweep: setup.sweep.clone(),
                group: index as u32 + 1,
                round,
                order,
                clocks,
            });
        }
        for running in group {
            let result = match running.failed {
                Some(error) => Err(error),
                None => Ok(running.timing),
            };
            closed.push(close(running.timed, result));
        }
    }
    closed
}

/// Each plan's warmup frames, then turns of one frame each until [`WARM_FOR`] has
/// passed (none without warmup frames).
fn warm<T>(setup: &Setup, group: &mut [Running<T>]) {
    if setup.warmup == 0 {
        return;
    }
    let start = Instant::now();
    let mut frames = setup.warmup as usize;
    loop {
        for running in group.iter_mut().filter(|r| r.failed.is_none()) {
            if let Err(error) = running.timed.prepared.run(frames) {
                running.failed = Some(error);
            }
        }
        if start.elapsed() >= WARM_FOR || group.iter().all(|r| r.failed.is_some()) {
            return;
        }
        frames = 1;
    }
}

/// One round: `--frames` frames of every plan still running, in order, with the clocks
/// sampled meanwhile: the names of the plans that ran, in order, and the sample.
fn run_round<T>(
    setup: &Setup,
    round: u32,
    group: &mut [Running<T>],
) -> (Vec<String>, Option<ClockSample>) {
    let device = &setup.session.gpu.device;
    let sample = setup.clocks.sample();
    let mut order = Vec::new();
    let mut ran = Vec::new();
    for (i, running) in group.iter_mut().enumerate() {
        if running.failed.is_some() {
            continue;
        }
        let before = Objects::alive(device);
        match running.timed.prepared.run(setup.frames as usize) {
            Ok(mut reports) => {
                if setup.fake_slow_round == Some(round) {
                    reports.iter_mut().for_each(slow_down);
                }
                let created = Objects::alive(device).minus(&before);
                if created.any() {
                    running.timing.created.push(created.in_round(round));
                }
                running.timing.rounds.push(reports);
                order.push(running.timed.name.clone());
                ran.push(i);
            }
            Err(error) => running.failed = Some(error),
        }
    }
    let clocks = sample.and_then(|pending| setup.clocks.finish(pending));
    for i in ran {
        group[i].timing.clocks.push(clocks.clone());
    }
    (order, clocks)
}

/// [`FAKE_SLOW_ROUND`]'s change to a frame: every GPU time ten times as long.
fn slow_down(report: &mut FrameReport) {
    let slower = |ns: u64| ns.saturating_mul(10);
    report.gpu_total_ns = report.gpu_total_ns.map(slower);
    for pass in &mut report.passes {
        pass.gpu_ns = pass.gpu_ns.map(slower);
    }
}

/// Consecutive groups of plans whose `sizes` add up to at most `budget` bytes; a plan
/// larger than the budget on its own is a group of its own.
pub fn groups(sizes: &[u64], budget: u64) -> Vec<Range<usize>> {
    let mut groups: Vec<Range<usize>> = Vec::new();
    let mut total = 0u64;
    for (i, &size) in sizes.iter().enumerate() {
        match groups.last_mut() {
            Some(last) if total.saturating_add(size) <= budget => {
                last.end = i + 1;
                total += size;
            }
            _ => {
                groups.push(i..i + 1);
                total = size;
            }
        }
    }
    groups
}

/// The pipelines and shader modules alive on a device (wgpu's `counters` feature, which
/// rgraph's Cargo.toml turns on): caches keep every one a plan creates, so a rise over
/// a plan's frames is what those frames compiled for the first time. The counts are of
/// objects alive, not of creations: a pipeline created to replace one the same frames
/// drop (a cache recompiling every frame) does not show.
struct Objects {
    render_pipelines: i64,
    compute_pipelines: i64,
    shader_modules: i64,
}

impl Objects {
    fn alive(device: &wgpu::Device) -> Objects {
        let hal = device.get_internal_counters().hal;
        Objects {
            render_pipelines: hal.render_pipelines.read() as i64,
            compute_pipelines: hal.compute_pipelines.read() as i64,
            shader_modules: hal.shader_modules.read() as i64,
        }
    }

    fn minus(&self, before: &Objects) -> Objects {
        Objects {
            render_pipelines: self.render_pipelines - before.render_pipelines,
            compute_pipelines: self.compute_pipelines - before.compute_pipelines,
            shader_modules: self.shader_modules - before.shader_modules,
        }
    }

    fn any(&self) -> bool {
        self.render_pipelines > 0 || self.compute_pipelines > 0 || self.shader_modules > 0
    }

    fn in_round(self, round: u32) -> Created {
        Created {
            round,
            render_pipelines: self.render_pipelines,
            compute_pipelines: self.compute_pipelines,
            shader_modules: self.shader_modules,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::groups;

    #[test]
    fn groups_stay_within_the_budget() {
        assert_eq!(groups(&[3, 3, 3, 3], 10), [0..3, 3..4]);
        assert_eq!(groups(&[3, 3, 3, 3], 100), vec![0..4; 1]);
        // A plan over the budget alone is measured alone; the next starts a group.
        assert_eq!(groups(&[2, 12, 2, 2], 10), [0..1, 1..2, 2..4]);
        assert!(groups(&[], 10).is_empty());
    }
}
