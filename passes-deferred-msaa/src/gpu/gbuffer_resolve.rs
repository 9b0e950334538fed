//! Recording the G-buffer resolve: one full-screen triangle writing the four resolved
//! targets and, through `frag_depth`, the depth.

use std::sync::Arc;

use graph_core::gpu::RenderContext;

use crate::common::depth::far_depth;
use crate::common::gpu::{per_scene, InputPass, PipelineDesc};
use crate::gpu_scene::SceneCache;
use crate::passes::gbuffer_resolve::GBufferResolveDraw;

#[derive(Clone, PartialEq)]
struct Key {
    targets: Vec<wgpu::TextureFormat>,
    depth: wgpu::TextureFormat,
}

pub(crate) fn record(
    draw: GBufferResolveDraw,
    scenes: Arc<SceneCache>,
) -> Box<dyn FnMut(&mut RenderContext<'_, '_>)> {
    let mut state = None;
    Box::new(move |ctx| {
        let resources = ctx.resources;
        let device = resources.device;
        // The camera turns the averaged view depth into depth.
        let Some(scene) = scenes.for_frame(resources) else {
            return;
        };
        let state = per_scene(&mut state, &scene, || {
            let label = "gbuffer resolve";
            InputPass::new(resources, label, &draw.source, Some(&scene), &draw.inputs)
        });
        let key = Key {
            targets: draw
                .targets
                .iter()
                .map(|&h| resources.shape(h).format)
                .collect(),
            depth: resources.shape(draw.depth).format,
        };
        let convention = draw.depth_rule.convention(key.depth);
        let pipeline = state.pipelines.get(key, |key| {
            let targets: Vec<Option<wgpu::ColorTargetState>> =
                key.targets.iter().map(|&f| Some(f.into())).collect();
            PipelineDesc {
                label: "gbuffer resolve",
                layout: &state.layout,
                module: &state.module,
                vertex: "vs_fullscreen",
                buffers: &[],
                fragment: "fs_resolve_gbuffer",
                constants: &[("FAR_DEPTH", f64::from(far_depth(convention)))],
                targets: &targets,
                cull: None,
                depth_stencil: Some(write_depth(key.depth)),
                samples: 1,
                mask: !0,
            }
            .build(device)
        });
        ctx.pass.set_pipeline(pipeline);
        ctx.pass
            .set_bind_group(0, scene.bind_group(convention), &[]);
        ctx.pass
            .set_bind_group(1, &state.inputs.bind_group(resources), &[]);
        ctx.pass.draw(0..3, 0..1);
    })
}

/// Every fragment writes its depth; stencil stays as cleared.
fn write_depth(format: wgpu::TextureFormat) -> wgpu::DepthStencilState {
    wgpu::DepthStencilState {
        format,
        depth_write_enabled: Some(true),
        depth_compare: Some(wgpu::CompareFunction::Always),
        stencil: wgpu::StencilState::default(),
        bias: Default::default(),
    }
}
