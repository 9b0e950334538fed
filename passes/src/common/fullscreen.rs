//! A full-screen draw of a deferred shader, as the edge, resolve, tone-mapping, debug and
//! transparent-composite plugins set it up, and (feature `gpu`) its recording: the edge
//! pass marks the stencil only, the others draw into a color target.

use rgraph_core::types::BlendState;
use rgraph_core::TextureHandle;

use super::extent::Extent;
use super::opaque_depth::OpaqueDepth;
use super::textures::Input;

#[cfg_attr(not(feature = "gpu"), allow(dead_code))]
pub(crate) struct Fullscreen {
    pub label: &'static str,
    /// The composed WGSL; its vertex entry point is `vs_fullscreen` (common.wgsl).
    pub source: String,
    pub entry: &'static str,
    pub constants: Vec<(&'static str, f64)>,
    /// Group 1.
    pub inputs: Vec<Input>,
    /// The shader reads the scene (group 0); without a host such a pass draws nothing.
    pub reads_scene: bool,
    /// The color attachment, if any.
    pub target: Option<TextureHandle>,
    /// Which of its pixels the draw covers (scissored; with `Blended` the pass needs a
    /// scene, and draws nothing when no blended mesh is in view).
    pub extent: Extent,
    /// A depth-stencil attachment whose stencil the pass marks: `Replace` with the
    /// reference 0x80 through write mask 0x80, wherever the shader does not discard.
    pub stencil_mark: Option<TextureHandle>,
    /// How the shader's output combines with the color attachment; `None` replaces it.
    pub blend: Option<BlendState>,
    /// The opaque depth the shader reads (group 1, with `inputs`), which sets its
    /// FAR_DEPTH and the convention of the camera in group 0.
    pub depth: Option<OpaqueDepth>,
}

impl Fullscreen {
    /// `entry` of `source` reading `inputs`, drawn over the whole of `target` (`None`
    /// for a pass that only marks the stencil): no constants, no scene, no stencil mark,
    /// the target's pixels replaced. A pass that needs more sets those fields over this
    /// (`Fullscreen { blend, ..Fullscreen::new(...) }`).
    pub fn new(
        label: &'static str,
        source: String,
        entry: &'static str,
        inputs: Vec<Input>,
        target: Option<TextureHandle>,
    ) -> Self {
        Fullscreen {
            label,
            source,
            entry,
            constants: Vec::new(),
            inputs,
            reads_scene: false,
            target,
            extent: Extent::Full,
            stencil_mark: None,
            blend: None,
            depth: None,
        }
    }
}

#[cfg(feature = "gpu")]
mod gpu {
    use std::sync::Arc;

    use rgraph_core::TextureHandle;

    use super::Fullscreen;
    use crate::common::depth::far_depth;
    use crate::common::extent::Extent;
    use crate::common::gpu::{
        Frame, InputPass, PipelineDesc, Recorded, Recorder, Render, EDGE_STENCIL,
    };
    use crate::common::opaque_depth::OpaqueDepth;
    use crate::gpu_scene::GpuScene;
    use rgraph_scene::DepthConvention;

    /// Attachment formats and sample count, as the plan made them, and the convention
    /// of the opaque depth read.
    #[derive(Clone, PartialEq)]
    pub(crate) struct Key {
        target: Option<wgpu::TextureFormat>,
        depth_stencil: Option<wgpu::TextureFormat>,
        samples: u32,
        convention: DepthConvention,
    }

    impl Recorder for Fullscreen {
        type Stage = Render;
        type Scene = Option<Arc<GpuScene>>;
        type State = InputPass<Key>;

        fn reads_scene(&self) -> bool {
            self.reads_scene
        }

        fn build(&self, frame: &Frame<'_, '_, Self>) -> Result<Self::State, String> {
            let bound =
                OpaqueDepth::bound_with(self.depth.as_ref(), &self.inputs, frame.resources)?;
            Ok(InputPass::with_geometry(
                frame.resources,
                self.label,
                &self.source,
                frame.scene.as_deref(),
                &bound.inputs,
                &bound.buffers,
                false,
            ))
        }

        fn record(&self, state: &mut Self::State, frame: &mut Frame<'_, '_, Self>) -> Recorded {
            let pass = &mut *frame.pass;
            let resources = frame.resources;
            if self.extent == Extent::Blended {
                let Some(rect_scene) = frame.scenes.for_frame(resources)? else {
                    return Ok(());
                };
                let target = self.target.or(self.stencil_mark);
                let size = target.map_or(resources.output_size(), |h| {
                    let shape = resources.shape(h);
                    (shape.width, shape.height)
                });
                let Some(rect) = self.extent.rect(&rect_scene, size) else {
                    return Ok(());
                };
                pass.set_scissor_rect(rect.x, rect.y, rect.width, rect.height);
            }
            let convention =
                OpaqueDepth::bound_with(self.depth.as_ref(), &self.inputs, resources)?.convention;
            let shape = |h: TextureHandle| resources.shape(h);
            let key = Key {
                target: self.target.map(|h| shape(h).format),
                depth_stencil: self.stencil_mark.map(|h| shape(h).format),
                samples: self
                    .target
                    .or(self.stencil_mark)
                    .map_or(1, |h| shape(h).samples),
                convention,
            };
            let pipeline = state.pipelines.get(key, |key| {
                let mut constants = self.constants.clone();
                if self.depth.is_some() {
                    constants.push(("FAR_DEPTH", f64::from(far_depth(key.convention))));
                }
                let targets = [key.target.map(|format| wgpu::ColorTargetState {
                    format,
                    blend: self.blend,
                    write_mask: wgpu::ColorWrites::ALL,
                })];
                PipelineDesc {
                    label: self.label,
                    layout: &state.layout,
                    module: &state.module,
                    vertex: "vs_fullscreen",
                    buffers: &[],
                    fragment: self.entry,
                    constants: &constants,
                    targets: if key.target.is_some() { &targets } else { &[] },
                    cull: None,
                    depth_stencil: key.depth_stencil.map(stencil_mark),
                    samples: key.samples,
                    mask: !0,
                }
                .build(frame.device)
            });
            pass.set_pipeline(pipeline);
            if let Some(scene) = &frame.scene {
                pass.set_bind_group(0, scene.bind_group(convention), &[]);
            }
            pass.set_bind_group(1, &state.inputs.bind_group(resources), &[]);
            pass.set_stencil_reference(EDGE_STENCIL);
            pass.draw(0..3, 0..1);
            Ok(())
        }
    }

    fn stencil_mark(format: wgpu::TextureFormat) -> wgpu::DepthStencilState {
        let mark = wgpu::StencilFaceState {
            compare: wgpu::CompareFunction::Always,
            fail_op: wgpu::StencilOperation::Keep,
            depth_fail_op: wgpu::StencilOperation::Keep,
            pass_op: wgpu::StencilOperation::Replace,
        };
        wgpu::DepthStencilState {
            format,
            depth_write_enabled: Some(false),
            depth_compare: Some(wgpu::CompareFunction::Always),
            stencil: wgpu::StencilState {
                front: mark,
                back: mark,
                read_mask: 0xff,
                write_mask: EDGE_STENCIL,
            },
            bias: Default::default(),
        }
    }
}
