//! What a pass that makes the shadow atlas remembers to keep it while nothing moved
//! (common/shadow_cache.rs).

use crate::gpu_scene::{ShadowStamp, ShadowWork};

/// The stamp of the work the atlas was last drawn from, by this pass of this executor.
#[derive(Default)]
pub(crate) struct Kept {
    drawn: Option<ShadowStamp>,
}

impl Kept {
    /// Whether the last frame's atlas holds this frame's maps, `work`: it was drawn from
    /// work of the same stamp, the history holding it was not `reset`, and no view draws
    /// an alpha MASK mesh. Where not, `work` is drawn this frame, and remembered.
    pub fn keeps(&mut self, work: &ShadowWork, reset: bool) -> bool {
        let kept = !reset && !work.draws_masked() && self.drawn.as_ref() == Some(&work.stamp);
        if !kept {
            self.drawn = Some(work.stamp.clone());
        }
        kept
    }
}
