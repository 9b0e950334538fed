//! Recording the forward pass: the scene into the HDR target alone, shaded per pixel or
//! per sample, masked materials selected by the `MASKED` pipeline constant.

use std::sync::Arc;

use graph_core::gpu::RenderContext;

use super::scene_draw::{self, SceneDraw, Stages};
use crate::analysis::GatedShader;
use crate::gpu_scene::SceneCache;
use crate::plugins::forward::{ForwardDraw, Shading};

pub(crate) fn record(
    draw: ForwardDraw,
    scenes: Arc<SceneCache>,
) -> Box<dyn FnMut(&mut RenderContext<'_, '_>)> {
    let (vertex, fragment) = match draw.shading {
        Shading::Pixel => ("vs_pixel", "fs_pixel"),
        Shading::Sample => ("vs_sample", "fs_sample"),
    };
    let draw = SceneDraw {
        label: "forward",
        shader: GatedShader::Forward,
        source: draw.source,
        depth_rule: draw.depth_rule,
        targets: vec![draw.hdr],
        depth: draw.depth,
        stages: Box::new(move |material| Stages {
            vertex,
            fragment,
            constants: vec![("MASKED", f64::from(u8::from(material.masked)))],
        }),
    };
    scene_draw::record(draw, scenes)
}
