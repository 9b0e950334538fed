//! The scene's first animation, played in real time and looped, posing each frame's
//! meshes.

use std::time::Instant;

use rgraph_passes::FrameInputs;
use rgraph_scene::{AnimationId, Scene};

/// The animation playing and when it started.
pub struct Playback {
    animation: AnimationId,
    started: Instant,
}

impl Playback {
    /// Plays `scene`'s first animation from now; `None` when it has none.
    pub fn first(scene: &Scene) -> Option<Playback> {
        scene.animation_ids().next().map(|animation| Playback {
            animation,
            started: Instant::now(),
        })
    }

    /// `inputs` with the meshes, joints and morph weights where the animation puts them
    /// now: its start plus the seconds since it started, wrapped to its span so that it
    /// loops.
    pub fn pose(&self, scene: &Scene, mut inputs: FrameInputs) -> FrameInputs {
        let clip = scene.animation(self.animation);
        let span = clip.end - clip.start;
        let elapsed = self.started.elapsed().as_secs_f64();
        let time = match span > 0.0 {
            true => clip.start + elapsed % span,
            false => clip.start,
        };
        inputs.set_pose(scene.animated_pose(self.animation, time));
        inputs.time = time;
        inputs
    }
}
