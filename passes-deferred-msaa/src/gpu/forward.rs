//! Recording the forward pass: the scene's opaque meshes into the HDR target alone,
//! shaded per pixel or per sample, masked materials selected by the `MASKED` pipeline
//! constant; and the transparent pass, its BLEND meshes into the accumulation target
//! with the same vertex stages and shading (plugins/transparent.rs).

use std::sync::Arc;

use graph_core::gpu::RenderContext;

use crate::analysis::GatedShader;
use crate::common::gpu::scene_draw::{self, SceneDraw, Stages};
use crate::gpu_scene::{Layer, SceneCache};
use crate::passes::forward::{ForwardDraw, Shading};

pub(crate) fn record(
    draw: ForwardDraw,
    scenes: Arc<SceneCache>,
) -> Box<dyn FnMut(&mut RenderContext<'_, '_>)> {
    let (label, shader, layer) = match draw.transparent {
        false => ("forward", GatedShader::Forward, Layer::Opaque),
        true => ("transparent", GatedShader::Transparent, Layer::Blended),
    };
    let (vertex, fragment) = match (draw.shading, draw.transparent) {
        (Shading::Pixel, false) => ("vs_pixel", "fs_pixel"),
        (Shading::Sample, false) => ("vs_sample", "fs_sample"),
        (Shading::Pixel, true) => ("vs_pixel", "fs_blend_pixel"),
        (Shading::Sample, true) => ("vs_sample", "fs_blend_sample"),
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
