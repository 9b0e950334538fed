//! A compute pass over every pixel of one output, a workgroup per 8 x 8 pixels, as the
//! compute tone mapper and the compute particle composite set it up, and (feature `gpu`)
//! its recording: the compute counterpart of [`super::fullscreen`], without the ROPs a
//! full-screen draw pays for every pixel it writes.

use graph_core::TextureHandle;

use super::opaque_depth::OpaqueDepth;
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
    /// The opaque depth the shader reads (group 1, with `inputs`), which sets its
    /// FAR_DEPTH and the convention of the camera in group 0.
    pub depth: Option<OpaqueDepth>,
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
    use crate::common::depth::far_depth;
    use crate::common::gpu::{compute_pipeline, per_device, InputPass};
    use crate::common::opaque_depth::{Bound, OpaqueDepth};
    use crate::gpu_scene::SceneCache;
    use rgraph_scene::DepthConvention;

    type State = InputPass<DepthConvention, wgpu::ComputePipeline>;

    pub(super) fn record(
        dispatch: FullscreenCompute,
        scenes: Arc<SceneCache>,
    ) -> Box<dyn FnMut(&mut ComputeContext<'_, '_>)> {
        // Built per device, as the full-screen passes are: the scene's group 0 layout is
        // the same for every upload.
        let mut state: Option<(wgpu::Device, State)> = None;
        Box::new(move |ctx| {
            let resources = ctx.resources;
            let device = resources.device;
            let Some(scene) = scenes.for_frame_if(dispatch.reads_scene, resources) else {
                return;
            };
            let bound =
                OpaqueDepth::bound_with(dispatch.depth.as_ref(), &dispatch.inputs, resources);
            let Bound {
                inputs,
                buffers,
                convention,
            } = match bound {
                Ok(bound) => bound,
                Err(why) => return resources.fail(why),
            };
            let state = per_device(&mut state, device, || {
                InputPass::with_geometry(
                    resources,
                    dispatch.label,
                    &dispatch.source,
                    scene.as_deref(),
                    &inputs,
                    &buffers,
                    false,
                )
            });
            let (module, layout) = (&state.module, &state.layout);
            let pipeline = state.pipelines.get(convention, |&convention| {
                let mut constants = dispatch.constants.clone();
                if dispatch.depth.is_some() {
                    constants.push(("FAR_DEPTH", f64::from(far_depth(convention))));
                }
                let entry = dispatch.entry;
                compute_pipeline(device, dispatch.label, layout, module, entry, &constants)
            });
            ctx.pass.set_pipeline(pipeline);
            if let Some(scene) = &scene {
                // The camera of the depth's convention (without a depth, the viewport
                // and the frame's exposure are all the shader reads).
                ctx.pass
                    .set_bind_group(0, scene.bind_group(convention), &[]);
            }
            ctx.pass
                .set_bind_group(1, &state.inputs.bind_group(resources), &[]);
            let out = resources.shape(dispatch.target);
            ctx.pass
                .dispatch_workgroups(out.width.div_ceil(8), out.height.div_ceil(8), 1);
        })
    }
}
