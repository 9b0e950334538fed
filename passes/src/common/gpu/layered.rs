//! Recording a pass set up with material-layer targets ([`Layered`],
//! common/gbuffer_layers.rs): each frame records the pass made for the layers its plan
//! keeps (`FrameResources::has`; the clear coat's normal as its target's format says),
//! made and built the first time a frame keeps that set on a device.

use super::{Frame, Recorded, Recorder};
use crate::common::gbuffer_layers::{LayerSet, Layered};

impl<R: Recorder> Recorder for Layered<R>
where
    R::Scene: Clone,
{
    type Stage = R::Stage;
    type Scene = R::Scene;
    /// Each set met, with its pass and what that pass built.
    type State = Vec<(LayerSet, R, R::State)>;

    /// The passes set up with layer targets light or draw the scene (their `Scene` is
    /// the scene's upload, which they always read).
    fn reads_scene(&self) -> bool {
        true
    }

    fn build(&self, _: &Frame<'_, '_, Self>) -> Result<Self::State, String> {
        Ok(Vec::new())
    }

    fn record(&self, state: &mut Self::State, frame: &mut Frame<'_, '_, Self>) -> Recorded {
        let resources = frame.resources;
        let set = LayerSet::kept(
            &self.targets,
            |h| resources.has(h),
            |h| resources.shape(h).format,
        );
        let mut frame = Frame {
            pass: &mut *frame.pass,
            resources,
            device: frame.device,
            scene: frame.scene.clone(),
            scenes: frame.scenes,
        };
        let at = match state.iter().position(|(s, ..)| *s == set) {
            Some(at) => at,
            None => {
                let recorder = (self.make)(set).map_err(|e| e.to_string())?;
                let built = recorder.build(&frame)?;
                state.push((set, recorder, built));
                state.len() - 1
            }
        };
        let (_, recorder, built) = &mut state[at];
        recorder.record(built, &mut frame)
    }
}
