//! Recording the G-buffer pass: the scene into the G-buffer's color targets, masked
//! materials through the fragment entry point that discards.

use std::sync::Arc;

use graph_core::gpu::RenderContext;

use crate::analysis::GatedShader;
use crate::common::gpu::scene_draw::{self, SceneDraw, Stages};
use crate::gpu_scene::{Layer, SceneCache};
use crate::passes::gbuffer::GBufferDraw;

pub(crate) fn record(
    draw: GBufferDraw,
    scenes: Arc<SceneCache>,
) -> Box<dyn FnMut(&mut RenderContext<'_, '_>)> {
    let draw = SceneDraw {
        label: "gbuffer",
        shader: GatedShader::GBuffer,
        source: draw.source,
        depth_rule: draw.depth_rule,
        targets: draw.targets,
        depth: draw.depth,
        layer: Layer::Opaque,
        stages: Box::new(|material| Stages {
            vertex: "vs_main",
            fragment: if material.masked {
                "fs_masked"
            } else {
                "fs_opaque"
            },
            constants: Vec::new(),
        }),
    };
    scene_draw::record(draw, scenes)
}
