//! What each frame of `render` draws: the scene's own frame inputs, the camera orbited by
//! `--orbit` and the meshes posed by `--animation` at the frame's `--time`.

use rgraph_passes::{FrameInputs, Host};
use rgraph_scene::glam::DVec3;
use rgraph_scene::AnimationId;

use super::error::RenderError;
use crate::cli::{RenderArgs, Time};
use crate::frame::FrameError;

/// The frame inputs of frame `index` of `--frames N`, computed from the first frame's.
pub struct Sequence {
    start: FrameInputs,
    /// The orbit's centre, the scene's bounds centre.
    center: DVec3,
    /// Radians the camera turns per frame.
    step: f64,
    /// The animation posing the meshes, the first frame's time and the seconds per frame.
    animation: Option<(AnimationId, f64, f64)>,
}

/// Fails when `--time` does not fit `--frames`: one frame takes one time, more take a
/// span. Checked before the scene loads.
pub fn check_time(args: &RenderArgs) -> Result<(), RenderError> {
    let frames = args.frames;
    match args.time {
        Some(Time::Span(start, end)) if frames == 1 => Err(RenderError::Time(format!(
            "--time {start}..{end} is a span, which --frames N above 1 covers; one frame \
             takes one time, e.g. --time {start}"
        ))),
        Some(Time::At(time)) if frames > 1 => Err(RenderError::Time(format!(
            "--frames {frames} covers a span of times: give --time T0..T1, or no --time for \
             the animation's first to last key time (--time {time} poses one frame)"
        ))),
        _ => Ok(()),
    }
}

impl Sequence {
    /// The sequence `args` asks for of the scene `host` draws. Fails when the scene has
    /// no animation `--animation` names, listing those it has.
    pub fn new(host: &Host, args: &RenderArgs) -> Result<Sequence, RenderError> {
        let scene = &host.scene;
        let intervals = f64::from(args.frames.saturating_sub(1).max(1));
        let animation = match &args.animation {
            None => None,
            Some(name) => {
                let id = scene.find_animation(name).map_err(FrameError::Scene)?;
                let clip = scene.animation(id);
                let (start, end) = match args.time {
                    Some(Time::At(time)) => (time, time),
                    Some(Time::Span(start, end)) => (start, end),
                    None => (clip.start, clip.end),
                };
                Some((id, start, (end - start) / intervals))
            }
        };
        Ok(Sequence {
            start: FrameInputs::clone(&host.frame()),
            center: scene.bounds.center(),
            step: args.orbit.to_radians() / intervals,
            animation,
        })
    }

    /// What the progress line says the frames do.
    pub fn describe(&self, host: &Host, frames: u32, orbit: f64) -> String {
        let mut what = format!("render {frames} frames, the camera orbiting {orbit}°");
        if let Some((id, start, step)) = self.animation {
            let end = start + step * f64::from(frames - 1);
            let name = &host.scene.animation(id).name;
            what += &format!(", animation \"{name}\" from {start} s to {end} s");
        }
        what
    }

    /// Frame `index`'s inputs: the first frame's, orbited and posed.
    pub fn inputs(&self, host: &Host, index: u32) -> FrameInputs {
        let index = f64::from(index);
        let mut inputs = FrameInputs {
            camera: (self.start.camera).orbited(self.center, self.step * index),
            ..self.start.clone()
        };
        if let Some((id, start, step)) = self.animation {
            inputs.time = start + step * index;
            inputs.set_pose(host.scene.animated_pose(id, inputs.time));
        }
        inputs
    }
}
