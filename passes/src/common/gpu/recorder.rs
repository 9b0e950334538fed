//! One shape for every pass's recording. A pass gives a [`Recorder`]: how to build its
//! device objects, and what to record each frame. [`declare`] makes it the pass's record
//! callback, which fetches the frame's scene (recording nothing without one, for a pass
//! that needs it), builds the objects on the first frame of a device and keeps them
//! (a scene cache uploads its scene once per device, so they serve every frame there),
//! and fails the frame with the reason a recorder returns (the executor names the pass).

use std::sync::Arc;

use rgraph_core::gpu::FrameResources;
use rgraph_core::PassBuilder;

use crate::gpu_scene::{GpuScene, SceneCache};

/// A pass as its plugin set it up, recorded on a device.
pub(crate) trait Recorder: Sized + 'static {
    /// A render or a compute pass.
    type Stage: Stage;
    /// What the pass takes of the host's scene ([`FrameScene`]).
    type Scene: FrameScene;
    /// What the pass builds on a device's first frame, and keeps.
    type State: 'static;

    /// With `Scene = Option<Arc<GpuScene>>`: whether the pass reads the scene.
    fn reads_scene(&self) -> bool {
        true
    }

    fn build(&self, frame: &Frame<'_, '_, Self>) -> Result<Self::State, String>;

    fn record(&self, state: &mut Self::State, frame: &mut Frame<'_, '_, Self>) -> Recorded;
}

/// A frame recorded, or why the device cannot record it.
pub(crate) type Recorded = Result<(), String>;

/// What a recorder records with, each frame.
pub(crate) struct Frame<'f, 'p, R: Recorder> {
    /// The begun render or compute pass.
    pub pass: &'f mut <R::Stage as Stage>::Pass<'p>,
    pub resources: &'f FrameResources<'f>,
    pub device: &'f wgpu::Device,
    pub scene: R::Scene,
    /// The scene's shader variants and texture table.
    pub scenes: &'f SceneCache,
}

/// The kind of pass a recorder records into.
pub(crate) trait Stage {
    type Pass<'p>;

    /// Gives `pass` the callback that calls `record` with the begun pass.
    fn declare(
        pass: &mut PassBuilder<'_>,
        record: impl FnMut(&mut Self::Pass<'_>, &FrameResources<'_>) + 'static,
    );
}

pub(crate) enum Render {}

impl Stage for Render {
    type Pass<'p> = wgpu::RenderPass<'p>;

    fn declare(
        pass: &mut PassBuilder<'_>,
        mut record: impl FnMut(&mut Self::Pass<'_>, &FrameResources<'_>) + 'static,
    ) {
        pass.render(move |ctx| record(ctx.pass, ctx.resources));
    }
}

pub(crate) enum Compute {}

impl Stage for Compute {
    type Pass<'p> = wgpu::ComputePass<'p>;

    fn declare(
        pass: &mut PassBuilder<'_>,
        mut record: impl FnMut(&mut Self::Pass<'_>, &FrameResources<'_>) + 'static,
    ) {
        pass.compute(move |ctx| record(ctx.pass, ctx.resources));
    }
}

/// What a recorder takes of the host's scene each frame: `Arc<GpuScene>` (the pass
/// records nothing without a host), `Option<Arc<GpuScene>>` (the scene where
/// [`Recorder::reads_scene`]) or `()` (nothing).
pub(crate) trait FrameScene: Sized {
    /// This frame's, `None` for a frame the pass records nothing in, or why the device
    /// cannot hold the scene.
    fn fetch(
        scenes: &SceneCache,
        resources: &FrameResources<'_>,
        reads: bool,
    ) -> Result<Option<Self>, String>;
}

impl FrameScene for Arc<GpuScene> {
    fn fetch(
        scenes: &SceneCache,
        resources: &FrameResources<'_>,
        _: bool,
    ) -> Result<Option<Self>, String> {
        scenes.for_frame(resources)
    }
}

impl FrameScene for Option<Arc<GpuScene>> {
    fn fetch(
        scenes: &SceneCache,
        resources: &FrameResources<'_>,
        reads: bool,
    ) -> Result<Option<Self>, String> {
        scenes.for_frame_if(reads, resources)
    }
}

impl FrameScene for () {
    fn fetch(_: &SceneCache, _: &FrameResources<'_>, _: bool) -> Result<Option<Self>, String> {
        Ok(Some(()))
    }
}

/// Gives `pass` `recorder`'s record callback; see the module documentation.
pub(crate) fn declare<R: Recorder>(
    pass: &mut PassBuilder<'_>,
    recorder: R,
    scenes: Arc<SceneCache>,
) {
    let mut built = None;
    R::Stage::declare(pass, move |pass, resources| {
        let scene = match R::Scene::fetch(&scenes, resources, recorder.reads_scene()) {
            Ok(Some(scene)) => scene,
            Ok(None) => return,
            Err(why) => return resources.fail(why),
        };
        let device = resources.device;
        let mut frame = Frame {
            pass,
            resources,
            device,
            scene,
            scenes: &scenes,
        };
        let recorded = state(&mut built, &recorder, &frame)
            .and_then(|state| recorder.record(state, &mut frame));
        if let Err(why) = recorded {
            resources.fail(why);
        }
    });
}

/// `built`'s state, built first where it was for another device (or not yet).
fn state<'s, R: Recorder>(
    built: &'s mut Option<(wgpu::Device, R::State)>,
    recorder: &R,
    frame: &Frame<'_, '_, R>,
) -> Result<&'s mut R::State, String> {
    let kept = match built.take() {
        Some((device, state)) if device == *frame.device => (device, state),
        _ => (frame.device.clone(), recorder.build(frame)?),
    };
    Ok(&mut built.insert(kept).1)
}
