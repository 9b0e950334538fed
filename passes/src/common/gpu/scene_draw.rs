//! Recording a pass that draws the scene's meshes ([`SceneDraw`]: the G-buffer, forward,
//! transparent and light pre-pass passes): one draw per mesh of the pass's [`Layer`],
//! with a pipeline per material state (culling, alpha mask) and attachment formats. The
//! passes differ only in shader, color targets, layer and entry points. Pipelines are
//! compiled for the scene's shader variant (variant.rs), which their key holds.
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
//! layer's beginning over the rectangle its meshes may cover
//! ([`GpuScene::blended_rect`]); after them, the background fill of the samples none
//! drew (common/background.rs).
//!
//! A redraw ([`SceneDraw::redraw`]) draws the opaque layer again over the depth an
//! earlier draw of the same shader module wrote.

use std::sync::Arc;

use super::bindings::TextureBindings;
use super::pipeline::{module, pipeline_layout, PipelineDesc, Pipelines};
use super::{Frame, Recorded, Recorder, Render};
use crate::common::depth::far_depth;
use crate::common::scene_draw::{Masked, SceneDraw};
use crate::common::textures::Input;
use crate::gpu_scene::{last_pose, mesh, GpuScene, Layer, MaterialState};
use crate::variant::Variant;
use rgraph_scene::DepthConvention;

#[derive(Clone, PartialEq)]
pub(crate) struct Key {
    targets: Vec<wgpu::TextureFormat>,
    depth: wgpu::TextureFormat,
    samples: u32,
    material: MaterialState,
    variant: Variant,
}

pub(crate) struct State {
    module: wgpu::ShaderModule,
    layout: wgpu::PipelineLayout,
    /// Group 2: a redraw's inputs and the shadow atlas, where the pass reads them.
    inputs: Option<TextureBindings>,
    pipelines: Pipelines<Key>,
    /// The full-screen draws' (the blended layer's beginning, the background fill): no
    /// bind groups, keyed by attachment formats and samples.
    fullscreen_layout: wgpu::PipelineLayout,
    begin_pipelines: Pipelines<FullscreenKey>,
    fill_pipelines: Pipelines<FullscreenKey>,
}

type FullscreenKey = (Vec<wgpu::TextureFormat>, wgpu::TextureFormat, u32);

impl Recorder for SceneDraw {
    type Stage = Render;
    type Scene = Arc<GpuScene>;
    type State = State;

    fn build(&self, frame: &Frame<'_, '_, Self>) -> Result<State, String> {
        let (device, scene) = (frame.device, &frame.scene);
        let read: Vec<Input> = (self.redraw.iter().flatten().copied())
            .chain(self.shadows)
            .collect();
        let inputs = (!read.is_empty()).then(|| TextureBindings::new(frame.resources, &read));
        let last_pose = self.last_pose.then(|| last_pose::layout(device));
        let layouts = [
            Some(scene.layout()),
            Some(scene.material_layout()),
            inputs.as_ref().map(|i| &i.layout),
            last_pose.as_ref(),
        ];
        let groups = match self.last_pose {
            true => &layouts[..],
            false => &layouts[..3],
        };
        Ok(State {
            module: module(device, self.label, &self.source),
            layout: pipeline_layout(device, groups),
            inputs,
            pipelines: Pipelines::default(),
            fullscreen_layout: pipeline_layout(device, &[]),
            begin_pipelines: Pipelines::default(),
            fill_pipelines: Pipelines::default(),
        })
    }

    fn record(&self, state: &mut State, frame: &mut Frame<'_, '_, Self>) -> Recorded {
        let pass = &mut *frame.pass;
        let (resources, device, scene) = (frame.resources, frame.device, &frame.scene);
        let variant = frame.scenes.variant(self.shader);
        let depth = resources.shape(self.depth);
        let targets: Vec<wgpu::TextureFormat> = self
            .targets
            .iter()
            .map(|&h| resources.shape(h).format)
            .collect();
        let convention = self.depth_rule.convention(depth.format);
        pass.set_bind_group(0, scene.bind_group(convention), &[]);
        if let Some(inputs) = &state.inputs {
            pass.set_bind_group(2, &inputs.bind_group(resources), &[]);
        }
        if self.last_pose {
            pass.set_bind_group(3, scene.last_pose_group(device), &[]);
        }
        let layer = match self.blended {
            false => Layer::Opaque,
            true => Layer::Blended,
        };
        let redraws = self.redraw.is_some();
        // A scene on the device has a host scene (for_frame returned it).
        let Some(host_scene) = frame.scenes.scene() else {
            return Ok(());
        };
        if let Some(entry) = self.begin_blended {
            let Some(rect) = scene.blended_rect((depth.width, depth.height)) else {
                return Ok(());
            };
            let key = (targets.clone(), depth.format, depth.samples);
            let pipeline = state.begin_pipelines.get(key, |key| {
                FullscreenDraw {
                    label: self.label,
                    vertex: "vs_fullscreen",
                    fragment: entry,
                    far_depth: None,
                }
                .build(device, &state.fullscreen_layout, &state.module, key)
            });
            pass.set_scissor_rect(rect.x, rect.y, rect.width, rect.height);
            pass.set_pipeline(pipeline);
            pass.draw(0..3, 0..1);
        }
        let materials = scene.material_groups(device, resources.queue, host_scene);
        scene.draw_meshes(pass, (1, materials), layer, |pass, _, material| {
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
                let masked = key.material.masked;
                let (fragment, mut constants) = match self.stages.masked {
                    Masked::Entry(entry) if masked => (entry, Vec::new()),
                    Masked::Entry(_) => (self.stages.fragment, Vec::new()),
                    Masked::Constant => {
                        let constant = ("MASKED", f64::from(u8::from(masked)));
                        (self.stages.fragment, vec![constant])
                    }
                };
                constants.extend(key.variant.constants());
                PipelineDesc {
                    label: self.label,
                    layout,
                    module,
                    vertex: self.stages.vertex,
                    buffers: &[Some(mesh::VERTEX_LAYOUT)],
                    fragment,
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
        if self.fill_background {
            let key = (targets.clone(), depth.format, depth.samples);
            let pipeline = state.fill_pipelines.get(key, |key| {
                FullscreenDraw {
                    label: self.label,
                    vertex: "vs_fullscreen_far",
                    fragment: "fs_background",
                    far_depth: Some(convention),
                }
                .build(device, &state.fullscreen_layout, &state.module, key)
            });
            pass.set_pipeline(pipeline);
            pass.draw(0..3, 0..1);
        }
        Ok(())
    }
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
