//! Recording a pass set up with and without its optional shadow atlas
//! ([`Shadowed`], common/shadows.rs): each frame records the variant the plan calls
//! for, the one without the atlas where the plan drops the read
//! (`FrameResources::has`), each built the first time it records on a device.

use super::{Frame, Recorded, Recorder};
use crate::common::shadows::Shadowed;

impl<R: Recorder> Recorder for Shadowed<R>
where
    R::Scene: Clone,
{
    type Stage = R::Stage;
    type Scene = R::Scene;
    /// With the atlas, and without.
    type State = [Option<R::State>; 2];

    fn reads_scene(&self) -> bool {
        self.with.reads_scene()
    }

    fn build(&self, _: &Frame<'_, '_, Self>) -> Result<Self::State, String> {
        Ok([None, None])
    }

    fn record(&self, state: &mut Self::State, frame: &mut Frame<'_, '_, Self>) -> Recorded {
        let [with, without] = state;
        let (recorder, built) = match &self.without {
            Some((atlas, recorder)) if !frame.resources.has(*atlas) => (recorder, without),
            _ => (&self.with, with),
        };
        let mut frame = Frame {
            pass: &mut *frame.pass,
            resources: frame.resources,
            device: frame.device,
            scene: frame.scene.clone(),
            scenes: frame.scenes,
        };
        let built = match built {
            Some(built) => built,
            None => built.insert(recorder.build(&frame)?),
        };
        recorder.record(built, &mut frame)
    }
}
