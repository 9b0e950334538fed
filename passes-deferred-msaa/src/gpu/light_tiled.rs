//! Recording the tiled light pass: one dispatch of a workgroup per tile over the output,
//! its pipeline compiled for the scene's light kinds (analysis/variant.rs) and the depth
//! format's convention, made on first use and kept.

use std::sync::Arc;

use graph_core::gpu::ComputeContext;

use crate::analysis::{GatedShader, Variant};
use crate::common::gpu::{per_scene, InputPass};
use crate::gpu_scene::SceneCache;
use crate::passes::light_tiled::TiledDispatch;
use crate::scene::DepthConvention;

#[derive(Clone, PartialEq)]
struct Key {
    convention: DepthConvention,
    variant: Variant,
}

pub(crate) fn record(
    dispatch: TiledDispatch,
    scenes: Arc<SceneCache>,
) -> Box<dyn FnMut(&mut ComputeContext<'_, '_>)> {
    let mut state = None;
    Box::new(move |ctx| {
        let resources = ctx.resources;
        let device = resources.device;
        let Some(scene) = scenes.for_frame(resources) else {
            return;
        };
        let state: &mut InputPass<Key, wgpu::ComputePipeline> =
            per_scene(&mut state, &scene, || {
                InputPass::new(
                    resources,
                    "light_tiled",
                    &dispatch.source,
                    Some(&scene),
                    &dispatch.inputs,
                )
            });
        let convention = dispatch
            .depth_rule
            .convention(resources.shape(dispatch.depth).format);
        let key = Key {
            convention,
            variant: scenes.variant(GatedShader::LightTiled),
        };
        let (module, layout) = (&state.module, &state.layout);
        let pipeline = state.pipelines.get(key, |key| {
            let mut constants = dispatch.constants.clone();
            constants.extend(key.variant.constants());
            device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some("light_tiled"),
                layout: Some(layout),
                module,
                entry_point: Some("cs_light_tiled"),
                compilation_options: wgpu::PipelineCompilationOptions {
                    constants: &constants,
                    // The shader initialises what it reads of workgroup memory.
                    zero_initialize_workgroup_memory: false,
                },
                cache: None,
            })
        });
        ctx.pass.set_pipeline(pipeline);
        ctx.pass
            .set_bind_group(0, scene.bind_group(convention), &[]);
        ctx.pass
            .set_bind_group(1, &state.inputs.bind_group(resources), &[]);
        let out = resources.shape(dispatch.output);
        ctx.pass.dispatch_workgroups(
            out.width.div_ceil(dispatch.tile),
            out.height.div_ceil(dispatch.tile),
            1,
        );
    })
}
