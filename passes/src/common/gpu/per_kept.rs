//! Recording a pass set up with optional textures ([`PerKept`],
//! common/optional_targets.rs): each frame records the pass made for the set of them its
//! plan keeps (`FrameResources::has`; a format where the set depends on it, as the clear
//! coat's normal does), made and built the first time a frame keeps that set on a device.

use super::{Frame, Recorded, Recorder};
use crate::common::optional_targets::{OptionalTargets, PerKept};

impl<T: OptionalTargets, R: Recorder> Recorder for PerKept<T, R>
where
    R::Scene: Clone,
{
    type Stage = R::Stage;
    type Scene = R::Scene;
    /// Each set met, with its pass and what that pass built.
    type State = Vec<(T::Set, R, R::State)>;

    /// The passes set up with optional textures light, draw or move the scene (their
    /// `Scene` is the scene's upload, which they always read).
    fn reads_scene(&self) -> bool {
        true
    }

    fn build(&self, _: &Frame<'_, '_, Self>) -> Result<Self::State, String> {
        Ok(Vec::new())
    }

    fn record(&self, state: &mut Self::State, frame: &mut Frame<'_, '_, Self>) -> Recorded {
        let resources = frame.resources;
        let set = self
            .targets
            .kept(&|h| resources.has(h), &|h| resources.shape(h).format);
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
