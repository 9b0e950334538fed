//! Recording the forward pass: one draw per mesh, with a pipeline per material state and
//! attachment formats, like the G-buffer pass but into the HDR target alone.

use std::sync::Arc;

use graph_core::gpu::RenderContext;

use super::gbuffer::depth_test;
use super::{PipelineDesc, Pipelines};
use crate::gpu_scene::{mesh, GpuScene, MaterialState, SceneCache};
use crate::plugins::forward::{ForwardDraw, Shading};

#[derive(Clone, PartialEq)]
struct Key {
    hdr: wgpu::TextureFormat,
    depth: wgpu::TextureFormat,
    samples: u32,
    material: MaterialState,
}

struct State {
    scene: Arc<GpuScene>,
    module: wgpu::ShaderModule,
    layout: wgpu::PipelineLayout,
    pipelines: Pipelines<Key>,
}

pub(crate) fn record(
    draw: ForwardDraw,
    scenes: Arc<SceneCache>,
) -> Box<dyn FnMut(&mut RenderContext<'_, '_>)> {
    let mut state: Option<State> = None;
    let (vertex, fragment) = match draw.shading {
        Shading::Pixel => ("vs_pixel", "fs_pixel"),
        Shading::Sample => ("vs_sample", "fs_sample"),
    };
    Box::new(move |ctx| {
        let resources = ctx.resources;
        let device = resources.device;
        let Some(scene) = scenes.get(device, resources.queue) else {
            return;
        };
        // The camera depends only on the aspect ratio, and the shader never reads the
        // viewport, so a target at a multiple of the output size (the reference) is fine.
        scene.prepare(resources.queue, resources.output_size());
        if state
            .as_ref()
            .is_none_or(|s| !Arc::ptr_eq(&s.scene, &scene))
        {
            let layouts = [Some(scene.layout()), Some(scene.material_layout())];
            state = Some(State {
                module: super::module(device, "forward", &draw.source),
                layout: super::pipeline_layout(device, &layouts),
                scene: scene.clone(),
                pipelines: Pipelines::default(),
            });
        }
        let Some(state) = state.as_mut() else { return };
        let (hdr, depth) = (resources.shape(draw.hdr), resources.shape(draw.depth));
        ctx.pass
            .set_bind_group(0, scene.bind_group(draw.convention), &[]);
        scene.draw_meshes(ctx.pass, 1, |pass, _, material| {
            let key = Key {
                hdr: hdr.format,
                depth: depth.format,
                samples: hdr.samples,
                material,
            };
            let (module, layout) = (&state.module, &state.layout);
            let pipeline = state.pipelines.get(key, |key| {
                let masked = f64::from(u8::from(key.material.masked));
                PipelineDesc {
                    label: "forward",
                    layout,
                    module,
                    vertex,
                    buffers: &[Some(mesh::VERTEX_LAYOUT)],
                    fragment,
                    constants: &[("MASKED", masked)],
                    targets: &[Some(key.hdr.into())],
                    cull: (!key.material.double_sided).then_some(wgpu::Face::Back),
                    depth_stencil: Some(depth_test(key.depth, draw.convention)),
                    samples: key.samples,
                    mask: !0,
                }
                .build(device)
            });
            pass.set_pipeline(pipeline);
            true
        });
    })
}
