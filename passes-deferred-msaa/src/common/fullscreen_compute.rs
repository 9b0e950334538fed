//! A compute pass over every pixel of one output, a workgroup per 8 x 8 pixels, as the
//! compute tone mapper and the compute particle composite set it up, and (feature `gpu`)
//! its recording: the compute counterpart of [`super::fullscreen`], without the ROPs a
//! full-screen draw pays for every pixel it writes.

use graph_core::TextureHandle;

use super::plugin::Recording;
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
}

impl Recording for FullscreenCompute {
    #[cfg(feature = "gpu")]
    fn record(self, scenes: std::sync::Arc<crate::gpu_scene::SceneCache>) -> graph_core::Record {
        graph_core::Record::Compute(gpu::record(self, scenes))
    }
}

#[cfg(feature = "gpu")]
mod gpu {
    use std::sync::Arc;

    use graph_core::gpu::ComputeContext;

    use super::FullscreenCompute;
    use crate::common::gpu::{compute_pipeline, per_device, InputPass};
    use crate::gpu_scene::SceneCache;
    use crate::scene::DepthConvention;

    pub(super) fn record(
        dispatch: FullscreenCompute,
        scenes: Arc<SceneCache>,
    ) -> Box<dyn FnMut(&mut ComputeContext<'_, '_>)> {
        // Built per device, as the full-screen passes are: the scene's group 0 layout is
        // the same for every upload.
        let mut state: Option<(wgpu::Device, InputPass<(), wgpu::ComputePipeline>)> = None;
        Box::new(move |ctx| {
            let resources = ctx.resources;
            let device = resources.device;
            let Some(scene) = scenes.for_frame_if(dispatch.reads_scene, resources) else {
                return;
            };
            let state = per_device(&mut state, device, || {
                InputPass::new(
                    resources,
                    dispatch.label,
                    &dispatch.source,
                    scene.as_deref(),
                    &dispatch.inputs,
                )
            });
            let (module, layout) = (&state.module, &state.layout);
            let pipeline = state.pipelines.get((), |_| {
                let constants = &dispatch.constants;
                compute_pipeline(
                    device,
                    dispatch.label,
                    layout,
                    module,
                    dispatch.entry,
                    constants,
                )
            });
            ctx.pass.set_pipeline(pipeline);
            if let Some(scene) = &scene {
                // The camera's viewport and the frame's exposure, not depth.
                ctx.pass
                    .set_bind_group(0, scene.bind_group(DepthConvention::ReversedZ), &[]);
            }
            ctx.pass
                .set_bind_group(1, &state.inputs.bind_group(resources), &[]);
            let out = resources.shape(dispatch.target);
            ctx.pass
                .dispatch_workgroups(out.width.div_ceil(8), out.height.div_ceil(8), 1);
        })
    }
}
