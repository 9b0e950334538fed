//! What a plan's interleaved rounds measured (rounds.rs times them), and the figures
//! every bench reports of them ([`Times`]): the still bench's rows (measure.rs) and the
//! motion bench's (motion.rs) alike.

use rgraph_core::gpu::{FrameReport, PassTiming};
use serde::Serialize;

use super::clocks::ClockSample;
use super::figures::PassFigures;
use super::flag::{judge, Created, Evidence, Flag};
use super::stats::Spread;

/// What a plan's rounds measured.
pub struct Timing {
    /// The measured frames' reports, per round.
    pub rounds: Vec<Vec<FrameReport>>,
    /// Device objects created inside measured frames, per round that created any.
    pub created: Vec<Created>,
    /// The clock sample of each round the plan ran in.
    pub clocks: Vec<Option<ClockSample>>,
}

impl Timing {
    /// Every measured frame's report, round after round.
    pub fn frames(&self) -> impl Iterator<Item = &FrameReport> {
        self.rounds.iter().flatten()
    }

    /// The GPU frame time over the rounds, `None` without timestamps.
    pub fn frame_ms(&self) -> Option<Spread> {
        Spread::of_rounds(
            self.rounds
                .iter()
                .map(|round| round.iter().filter_map(|r| r.gpu_total_ns)),
        )
    }

    /// The frame's and each pass's times over the rounds, and the flag when the frame
    /// time's rounds disagree.
    pub fn times(&self) -> Times {
        let rounds = &self.rounds;
        let first = rounds.iter().flatten().next();
        let passes = first.map_or(Vec::new(), |first| {
            first
                .passes
                .iter()
                .enumerate()
                .map(|(i, pass)| {
                    let per_round =
                        |value: fn(&PassTiming) -> Option<u64>| {
                            Spread::of_rounds(rounds.iter().map(|round| {
                                round.iter().filter_map(move |r| value(r.passes.get(i)?))
                            }))
                        };
                    PassFigures {
                        name: pass.name.clone(),
                        kind: pass.kind.to_string(),
                        gpu_ms: per_round(|t| t.gpu_ns),
                        cpu_ms: per_round(|t| Some(t.cpu_ns)),
                    }
                })
                .collect()
        });
        let gpu_frame_ms = self.frame_ms();
        let flag = gpu_frame_ms.as_ref().and_then(|time| {
            judge(&Evidence {
                time,
                created: &self.created,
                clocks: &self.clocks,
            })
        });
        Times {
            gpu_frame_ms,
            flag,
            created_while_measured: self.created.clone(),
            cpu_record_ms: Spread::of_rounds(rounds.iter().map(|round| {
                round
                    .iter()
                    .map(|r| r.passes.iter().map(|p| p.cpu_ns).sum::<u64>())
            })),
            passes,
        }
    }
}

/// A timed plan's figures, as results.json's rows and motion.json's rows give them.
#[derive(Debug, Serialize)]
pub struct Times {
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
    /// Executed passes in order.
    pub passes: Vec<PassFigures>,
}
