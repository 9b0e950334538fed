//! Recording the forward pass: the scene's opaque meshes into the HDR target alone,
//! shaded per pixel or per sample, masked materials selected by the `MASKED` pipeline
//! constant; and the transparent pass, its BLEND meshes into the accumulation target
//! with the same vertex stages and shading (plugins/transparent.rs).

use std::sync::Arc;

use graph_core::gpu::RenderContext;

use super::scene_draw::{self, SceneDraw, Stages};
use crate::analysis::GatedShader;
use crate::gpu_scene::{Layer, SceneCache};
use crate::plugins::forward::{ForwardDraw, Shading};

pub(crate) fn record(
    draw: ForwardDraw,
    scenes: Arc<SceneCache>,
) -> Box<dyn FnMut(&mut RenderContext<'_, '_>)> {
    let vertex = match draw.shading {
        Shading::Pixel => "vs_pixel",
        Shading::Sample => "vs_sample",
    };
    let (label, shader, layer, fragment) = match (draw.transparent, draw.shading) {
        (false, Shading::Pixel) => ("forward", GatedShader::Forward, Layer::Opaque, "fs_pixel"),
        (false, Shading::Sample) => ("forward", GatedShader::Forward, Layer::Opaque, "fs_sample"),
        (true, Shading::Pixel) => (
            "transparent",
            GatedShader::Transparent,
            Layer::Blended,
            "fs_blend_pixel",
        ),
        (true, Shading::Sample) => (
            "transparent",
            GatedShader::Transparent,
            Layer::Blended,
            "fs_blend_sample",
        ),
    };
    let draw = SceneDraw {
        label,
        shader,
        source: draw.source,
        depth_rule: draw.depth_rule,
        targets: vec![draw.hdr],
        depth: draw.depth,
        layer,
        stages: Box::new(move |material| Stages {
            vertex,
            fragment,
            constants: vec![("MASKED", f64::from(u8::from(material.masked)))],
        }),
    };
    scene_draw::record(draw, scenes)
}
