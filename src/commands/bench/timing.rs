//! What a plan's interleaved rounds measured (rounds.rs times them, measure.rs turns the
//! timings into a row's figures).

use rgraph_core::gpu::FrameReport;

use super::clocks::ClockSample;
use super::flag::Created;

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
}
