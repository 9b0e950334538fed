//! Memory a pipeline asks for: every graph texture on its own and after pooling, the
//! buffers its passes keep for themselves, and the G-buffer's bytes per sample.

use rgraph_core::gpu::FrameReport;
use rgraph_core::{Plan, PlannedPass};
use serde::Serialize;

/// The passes whose attachments are the G-buffer, in every deferred pipeline (their
/// alternatives under conditions are named "gbuffer (...)"): a G-buffer, or a visibility
/// buffer's IDs and depth.
const GBUFFER_PASSES: [&str; 2] = ["gbuffer", "visibility"];

#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Memory {
    /// Every live graph texture and buffer on its own.
    pub logical_bytes: u64,
    /// What the executor allocates after textures of equal shape share memory.
    pub physical_bytes: u64,
    /// Buffers the passes keep for themselves (a compute rasteriser's bins, a list of
    /// edge pixels: FrameReport::held_bytes), which the plan does not count: the most a
    /// measured frame held.
    pub pass_bytes: u64,
    /// Bytes per sample of the G-buffer pass's color attachments, counted as WebGPU's
    /// `maxColorAttachmentBytesPerSample` counts them (each target aligned to its
    /// component size); `None` without a "gbuffer" pass (forward pipelines).
    pub gbuffer_bytes_per_sample: Option<u32>,
    /// What one sample of the G-buffer pass's attachments occupies, depth-stencil
    /// included (D32S8 as 8 bytes): the G-buffer's real size.
    pub gbuffer_stored_bytes_per_sample: Option<u32>,
}

impl Memory {
    /// The memory of `plan`, with what its passes kept for themselves in `frames`.
    pub fn of(plan: &Plan, frames: &[FrameReport]) -> Memory {
        let pass_bytes = frames
            .iter()
            .map(FrameReport::held_bytes)
            .max()
            .unwrap_or(0);
        Memory {
            logical_bytes: plan.memory.logical_bytes,
            physical_bytes: plan.memory.physical_bytes,
            pass_bytes,
            gbuffer_bytes_per_sample: gbuffer(plan).map(|p| p.color_bytes_per_sample),
            gbuffer_stored_bytes_per_sample: gbuffer(plan).map(|p| p.stored_bytes_per_sample),
        }
    }

    /// Every texture and buffer on its own, the passes' own included.
    pub fn total_bytes(&self) -> u64 {
        self.logical_bytes + self.pass_bytes
    }

    /// What is allocated after pooling, the passes' own buffers included.
    pub fn allocated_bytes(&self) -> u64 {
        self.physical_bytes + self.pass_bytes
    }
}

fn gbuffer(plan: &Plan) -> Option<&PlannedPass> {
    plan.passes.iter().find(|p| is_gbuffer(&p.name))
}

/// "gbuffer" or "visibility", or one of their alternatives under a condition,
/// "gbuffer (unlit)".
fn is_gbuffer(pass: &str) -> bool {
    GBUFFER_PASSES.iter().any(|name| {
        pass.strip_prefix(name)
            .is_some_and(|rest| rest.is_empty() || rest.starts_with(" ("))
    })
}
