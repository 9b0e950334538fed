//! A compute pass over every pixel of one output, a workgroup per 8 x 8 pixels, as the
//! compute tone mapper and the compute particle composite set it up, and (feature `gpu`)
//! its recording: the compute counterpart of [`super::fullscreen`], without the ROPs a
//! full-screen draw pays for every pixel it writes.

use rgraph_core::TextureHandle;

use super::opaque_depth::OpaqueDepth;
use super::textures::Input;

#[cfg_attr(not(feature = "gpu"), allow(dead_code))]
pub(crate) struct FullscreenCompute {
    pub label: &'static str,
    /// The composed WGSL, with `entry` of workgroup size 8 x 8.
    pub source: String,
    pub entry: &'static str,
    pub constants: Vec<(&'static str, f64)>,
    /// Group 1, the stored output among them.
    pub inputs: Vec<Input>,
    /// The shader reads the scene (group 0); without a host such a pass does nothing.
    pub reads_scene: bool,
    /// The output whose pixels the dispatch covers.
    pub target: TextureHandle,
    /// The opaque depth the shader reads (group 1, with `inputs`), which sets its
    /// FAR_DEPTH and the convention of the camera in group 0.
    pub depth: Option<OpaqueDepth>,
}

#[cfg(feature = "gpu")]
mod gpu {
    use std::sync::Arc;

    use super::FullscreenCompute;
    use crate::common::depth::far_depth;
    use crate::common::gpu::{compute_pipeline, Compute, Frame, InputPass, Recorded, Recorder};
    use crate::common::opaque_depth::OpaqueDepth;
    use crate::gpu_scene::GpuScene;
    use rgraph_scene::DepthConvention;

    impl Recorder for FullscreenCompute {
        type Stage = Compute;
        type Scene = Option<Arc<GpuScene>>;
        type State = InputPass<DepthConvention, wgpu::ComputePipeline>;

        fn reads_scene(&self) -> bool {
            self.reads_scene
        }

        fn build(&self, frame: &Frame<'_, '_, Self>) -> Result<Self::State, String> {
            let bound =
                OpaqueDepth::bound_with(self.depth.as_ref(), &self.inputs, frame.resources)?;
            Ok(InputPass::with_geometry(
                frame.resources,
                self.label,
                &self.source,
                frame.scene.as_deref(),
                &bound.inputs,
                &bound.buffers,
                false,
            ))
        }

        fn record(&self, state: &mut Self::State, frame: &mut Frame<'_, '_, Self>) -> Recorded {
            let pass = &mut *frame.pass;
            let resources = frame.resources;
            let convention =
                OpaqueDepth::bound_with(self.depth.as_ref(), &self.inputs, resources)?.convention;
            let (module, layout) = (&state.module, &state.layout);
            let pipeline = state.pipelines.get(convention, |&convention| {
                let mut constants = self.constants.clone();
                if self.depth.is_some() {
                    constants.push(("FAR_DEPTH", f64::from(far_depth(convention))));
                }
                compute_pipeline(
                    frame.device,
                    self.label,
                    layout,
                    module,
                    self.entry,
                    &constants,
                )
            });
            pass.set_pipeline(pipeline);
            if let Some(scene) = &frame.scene {
                // The camera of the depth's convention (without a depth, the viewport
                // and the frame's exposure are all the shader reads).
                pass.set_bind_group(0, scene.bind_group(convention), &[]);
            }
            pass.set_bind_group(1, &state.inputs.bind_group(resources), &[]);
            let out = resources.shape(self.target);
            pass.dispatch_workgroups(out.width.div_ceil(8), out.height.div_ceil(8), 1);
            Ok(())
        }
    }
}
