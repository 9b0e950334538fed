//! Recording a pass that draws the scene's meshes (the G-buffer, forward and transparent
//! passes): one draw per mesh of the pass's [`Layer`], with a pipeline per material state
//! (culling, alpha mask) and attachment formats. The passes differ only in shader, color
//! targets, layer and the entry points and constants a material state takes. Pipelines
//! are compiled for the scene's shader variant (variant.rs), which their key
//! holds.
//!
//! The opaque layer writes depth and replaces colour. The blended layer tests depth
//! without writing it (the depth-stencil is attached read-only) and accumulates as seed
//! 001 does for off-screen particles: colour by conventional alpha blending
//! (`src * a + dst * (1 - a)`) and alpha by the product of `1 - a` (source factor zero,
//! destination `1 - a`), so a target cleared to (0, 0, 0, 1) ends as the blended colour
//! over black and the transmittance of everything drawn.
//!
//! Where a pass begins its targets without a clear (a multisampled clear costs the H200 a
//! full-screen pass), a full-screen draw frames the meshes: before them, the blended
//! layer's beginning over the rectangle its meshes may cover (`begin_blended`); after
//! them, the background fill of the samples none drew (`fill_background`,
//! common/background.rs).
//!
//! A [`Redraw`] draws the opaque layer again over the depth an earlier draw of the same
//! shader module wrote (the light pre-pass's material pass): tested for the same or a
//! nearer depth without writing it, reading textures as group 2.

use std::sync::Arc;

use graph_core::gpu::RenderContext;
use graph_core::TextureHandle;

use super::bindings::TextureBindings;
use super::per_scene;
use super::pipeline::{module, pipeline_layout, PipelineDesc, Pipelines};
use crate::common::depth::{far_depth, DepthRule};
use crate::common::textures::Input;
use crate::gpu_scene::{mesh, Layer, MaterialState, SceneCache};
use crate::variant::{GatedShader, Variant};
use rgraph_scene::DepthConvention;

/// What a material state draws with.
pub(crate) struct Stages {
    pub vertex: &'static str,
    pub fragment: &'static str,
    /// Pipeline-overridable constants, given to both stages.
    pub constants: Vec<(&'static str, f64)>,
}

/// One scene-drawing pass.
pub(crate) struct SceneDraw {
    pub label: &'static str,
    pub shader: GatedShader,
    pub source: String,
    /// Resolved against the depth attachment's format when recording.
    pub depth_rule: DepthRule,
    /// Color attachments in location order.
    pub targets: Vec<TextureHandle>,
    pub depth: TextureHandle,
    pub layer: Layer,
    /// Begins the targets over the rectangle the blended meshes may cover
    /// ([`GpuScene::blended_rect`]) with this fragment entry point of the pass's module
    /// (after common.wgsl's `vs_fullscreen`, writing every target, depth neither tested nor
    /// written), and keeps the meshes' draws to it; nothing is drawn when no blended mesh
    /// is in view. For targets the pass begins without a clear (the transparent
    /// accumulation with `extent: blended`), whose other pixels nothing reads.
    ///
    /// [`GpuScene::blended_rect`]: crate::gpu_scene::GpuScene::blended_rect
    pub begin_blended: Option<&'static str>,
    /// After the meshes, fills what they left undrawn with the module's `fs_background`
    /// (common/background.rs): for targets begun without a clear, over a depth the pass
    /// cleared.
    pub fill_background: bool,
    pub stages: Box<dyn Fn(MaterialState) -> Stages>,
}

/// What a second draw over the depth of a first one reads (group 2). The pass attaches
/// the depth-stencil read-only.
pub(crate) struct Redraw {
    pub inputs: Vec<Input>,
}

#[derive(Clone, PartialEq)]
struct Key {
    targets: Vec<wgpu::TextureFormat>,
    depth: wgpu::TextureFormat,
    samples: u32,
    material: MaterialState,
    variant: Variant,
}

struct State {
    module: wgpu::ShaderModule,
    layout: wgpu::PipelineLayout,
    /// A redraw's group 2.
    inputs: Option<TextureBindings>,
    pipelines: Pipelines<Key>,
    /// The full-screen draws' (the blended layer's beginning, the background fill): no
    /// bind groups, keyed by attachment formats and samples.
    fullscreen_layout: wgpu::PipelineLayout,
    begin_pipelines: Pipelines<FullscreenKey>,
    fill_pipelines: Pipelines<FullscreenKey>,
}

type FullscreenKey = (Vec<wgpu::TextureFormat>, wgpu::TextureFormat, u32);

pub(crate) fn record(
    draw: SceneDraw,
    scenes: Arc<SceneCache>,
) -> Box<dyn FnMut(&mut RenderContext<'_, '_>)> {
    record_with(draw, None, scenes)
}

/// [`record`], as a [`Redraw`] when given one.
pub(crate) fn record_with(
    draw: SceneDraw,
    redraw: Option<Redraw>,
    scenes: Arc<SceneCache>,
) -> Box<dyn FnMut(&mut RenderContext<'_, '_>)> {
    let mut state = None;
    Box::new(move |ctx| {
        let resources = ctx.resources;
        let device = resources.device;
        let Some(scene) = scenes.for_frame(resources) else {
            return;
        };
        let state = per_scene(&mut state, &scene, || {
            let inputs = redraw
                .as_ref()
                .map(|r| TextureBindings::new(resources, &r.inputs));
            let layouts = [
                Some(scene.layout()),
                Some(scene.material_layout()),
                inputs.as_ref().map(|i| &i.layout),
            ];
            State {
                module: module(device, draw.label, &draw.source),
                layout: pipeline_layout(device, &layouts),
                inputs,
                pipelines: Pipelines::default(),
                fullscreen_layout: pipeline_layout(device, &[]),
                begin_pipelines: Pipelines::default(),
                fill_pipelines: Pipelines::default(),
            }
        });
        let variant = scenes.variant(draw.shader);
        let depth = resources.shape(draw.depth);
        let targets: Vec<wgpu::TextureFormat> = draw
            .targets
            .iter()
            .map(|&h| resources.shape(h).format)
            .collect();
        let convention = draw.depth_rule.convention(depth.format);
        ctx.pass
            .set_bind_group(0, scene.bind_group(convention), &[]);
        if let Some(inputs) = &state.inputs {
            ctx.pass
                .set_bind_group(2, &inputs.bind_group(resources), &[]);
        }
        let layer = draw.layer;
        let redraws = state.inputs.is_some();
        // A scene on the device has a host scene (for_frame returned it).
        let Some(host_scene) = scenes.scene() else {
            return;
        };
        if let Some(entry) = draw.begin_blended {
            let Some(rect) = scene.blended_rect((depth.width, depth.height)) else {
                return;
            };
            let key = (targets.clone(), depth.format, depth.samples);
            let pipeline = state.begin_pipelines.get(key, |key| {
                FullscreenDraw {
                    label: draw.label,
                    vertex: "vs_fullscreen",
                    fragment: entry,
                    far_depth: None,
                }
                .build(device, &state.fullscreen_layout, &state.module, key)
            });
            ctx.pass
                .set_scissor_rect(rect.x, rect.y, rect.width, rect.height);
            ctx.pass.set_pipeline(pipeline);
            ctx.pass.draw(0..3, 0..1);
        }
        let materials = scene.material_groups(device, resources.queue, host_scene);
        scene.draw_meshes(ctx.pass, (1, materials), layer, |pass, _, material| {
            let key = Key {
                targets: targets.clone(),
                depth: depth.format,
                samples: depth.samples,
                material,
                variant: variant.clone(),
            };
            let (module, layout) = (&state.module, &state.layout);
            let pipeline = state.pipelines.get(key, |key| {
                let targets: Vec<Option<wgpu::ColorTargetState>> = key
                    .targets
                    .iter()
                    .map(|&format| Some(color_target(format, layer)))
                    .collect();
                let stages = (draw.stages)(key.material);
                let mut constants = stages.constants;
                constants.extend(key.variant.constants());
                PipelineDesc {
                    label: draw.label,
                    layout,
                    module,
                    vertex: stages.vertex,
                    buffers: &[Some(mesh::VERTEX_LAYOUT)],
                    fragment: stages.fragment,
                    constants: &constants,
                    targets: &targets,
                    cull: (!key.material.double_sided).then_some(wgpu::Face::Back),
                    depth_stencil: Some(depth_test(key.depth, convention, layer, redraws)),
                    samples: key.samples,
                    mask: !0,
                }
                .build(device)
            });
            pass.set_pipeline(pipeline);
            true
        });
        if draw.fill_background {
            let key = (targets.clone(), depth.format, depth.samples);
            let pipeline = state.fill_pipelines.get(key, |key| {
                FullscreenDraw {
                    label: draw.label,
                    vertex: "vs_fullscreen_far",
                    fragment: "fs_background",
                    far_depth: Some(convention),
                }
                .build(device, &state.fullscreen_layout, &state.module, key)
            });
            ctx.pass.set_pipeline(pipeline);
            ctx.pass.draw(0..3, 0..1);
        }
    })
}

/// A full-screen triangle over a scene pass's attachments, replacing every target's
/// colour, writing no depth and no stencil: tested `Always`, or with `far_depth` drawn at
/// that convention's far depth and tested `Equal`, so that it covers exactly the samples
/// no mesh drew (the depth the pass cleared).
struct FullscreenDraw<'a> {
    label: &'a str,
    vertex: &'a str,
    fragment: &'a str,
    far_depth: Option<DepthConvention>,
}

impl FullscreenDraw<'_> {
    fn build(
        &self,
        device: &wgpu::Device,
        layout: &wgpu::PipelineLayout,
        module: &wgpu::ShaderModule,
        (targets, depth, samples): &FullscreenKey,
    ) -> wgpu::RenderPipeline {
        let targets: Vec<Option<wgpu::ColorTargetState>> = targets
            .iter()
            .map(|&format| Some(color_target(format, Layer::Opaque)))
            .collect();
        let (compare, constants) = match self.far_depth {
            None => (wgpu::CompareFunction::Always, Vec::new()),
            Some(convention) => (
                wgpu::CompareFunction::Equal,
                vec![("FAR_DEPTH", f64::from(far_depth(convention)))],
            ),
        };
        PipelineDesc {
            label: self.label,
            layout,
            module,
            vertex: self.vertex,
            buffers: &[],
            fragment: self.fragment,
            constants: &constants,
            targets: &targets,
            cull: None,
            depth_stencil: Some(wgpu::DepthStencilState {
                format: *depth,
                depth_write_enabled: Some(false),
                depth_compare: Some(compare),
                stencil: wgpu::StencilState::default(),
                bias: Default::default(),
            }),
            samples: *samples,
            mask: !0,
        }
        .build(device)
    }
}

/// Replacing for the opaque layer; seed 001's accumulation for the blended one (see the
/// module documentation).
fn color_target(format: wgpu::TextureFormat, layer: Layer) -> wgpu::ColorTargetState {
    let blend = match layer {
        Layer::Opaque => None,
        Layer::Blended => Some(wgpu::BlendState {
            color: wgpu::BlendComponent {
                src_factor: wgpu::BlendFactor::SrcAlpha,
                dst_factor: wgpu::BlendFactor::OneMinusSrcAlpha,
                operation: wgpu::BlendOperation::Add,
            },
            alpha: wgpu::BlendComponent {
                src_factor: wgpu::BlendFactor::Zero,
                dst_factor: wgpu::BlendFactor::OneMinusSrcAlpha,
                operation: wgpu::BlendOperation::Add,
            },
        }),
    };
    wgpu::ColorTargetState {
        format,
        blend,
        write_mask: wgpu::ColorWrites::ALL,
    }
}

/// Nearer fragments win: `Greater` with reversed Z, `Less` without. Only the opaque layer
/// writes depth: blended surfaces are hidden by opaque ones but never hide each other
/// (they are drawn back to front instead). A redraw passes where its surface is the one
/// drawn before (`GreaterEqual`, `LessEqual`: the same vertex code gives the same depth)
/// and writes nothing. Stencil is left alone (cleared to 0 by the G-buffer pass; the edge
/// pass marks it).
pub(crate) fn depth_test(
    format: wgpu::TextureFormat,
    convention: DepthConvention,
    layer: Layer,
    redraw: bool,
) -> wgpu::DepthStencilState {
    wgpu::DepthStencilState {
        format,
        depth_write_enabled: Some(layer == Layer::Opaque && !redraw),
        depth_compare: Some(match (convention, redraw) {
            (DepthConvention::ReversedZ, false) => wgpu::CompareFunction::Greater,
            (DepthConvention::Standard, false) => wgpu::CompareFunction::Less,
            (DepthConvention::ReversedZ, true) => wgpu::CompareFunction::GreaterEqual,
            (DepthConvention::Standard, true) => wgpu::CompareFunction::LessEqual,
        }),
        stencil: wgpu::StencilState::default(),
        bias: Default::default(),
    }
}
