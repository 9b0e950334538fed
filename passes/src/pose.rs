//! Where a plan moves a deformed scene's G-buffer points without their pose offset, for
//! tools that warn about it (`rgraph render`).
//!
//! A depth buffer's point has no triangle to take back to the last pose of a skin or
//! morph targets, so the G-buffer writes each sample's pose offset (common/pose_offset.rs)
//! and the motion vectors read it back. The shipped TAA presets declare its target under
//! `untabled_textures & deformed & color_bytes_64` and list the slot optional: on a device
//! without room for it the plan drops the read, and a deformed surface's pixels move
//! with their mesh's transform alone.

use rgraph_core::file::LoadedGraph;
use rgraph_core::{Plan, PlannedPass};

use crate::common::pose_offset::SLOT;

/// The scene feature of skins and morph targets.
const DEFORMED: &str = "deformed";

/// The first `motion_vectors` pass of `plan` (compiled from `loaded`) whose file gives it
/// a pose offset that the plan does not read, where `plan` was compiled for a scene with
/// deformations (feature `deformed`): its deformed points move with their mesh's transform
/// alone. None for a scene without them, or where every such pass reads the offset.
pub fn unposed<'p>(plan: &'p Plan, loaded: &LoadedGraph) -> Option<&'p str> {
    if !plan.features.iter().any(|f| f == DEFORMED) {
        return None;
    }
    let unposed = |pass: &&PlannedPass| {
        loaded.plugin(&pass.name) == Some("motion_vectors")
            && loaded
                .slot(&pass.name, SLOT)
                .is_some_and(|slot| !pass.reads_resource(slot.id()))
    };
    plan.passes
        .iter()
        .find(unposed)
        .map(|pass| pass.name.as_str())
}
