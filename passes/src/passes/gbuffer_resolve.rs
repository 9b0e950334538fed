//! `gbuffer_resolve`: averages a multisampled G-buffer into a single-sampled one plus a
//! depth-stencil, so `light_nonedge` can light it once per pixel: the wrong way to combine
//! deferred shading with MSAA that seed 000 warns about (figure 2.8.3), kept as a baseline
//! to measure against.
//!
//! ```ron
//! (name: "resolve gbuffer", plugin: "gbuffer_resolve",
//!  params: (reversed_z: true),   // optional: left out, it follows the depth format
//!  inputs: {                      // the multisampled G-buffer
//!      "albedo": "albedo", "normal": "normal", "material": "material",
//!      "view_depth": "view_depth",
//!  },
//!  outputs: {                     // the same formats, 1 sample
//!      "resolved_albedo": "albedo_1x", "resolved_normal": "normal_1x",
//!      "resolved_material": "material_1x", "resolved_view_depth": "view_depth_1x",
//!      "depth": "depth_1x",       // depth24plus-stencil8 or depth32float-stencil8, 1 sample
//!  })
//! ```
//!
//! A full-screen pass; gbuffer_resolve.wgsl says what each target's resolve is. The depth
//! written is the averaged view depth projected by the scene's camera (far where no sample
//! has geometry), so the light passes' depth tests see the same averaged surface as their
//! shading; stencil is cleared to 0, so `light_nonedge` shades every pixel. Emission and
//! unlit colors are in the G-buffer's HDR target: resolve that with `resolve`.

use serde::Deserialize;

use rgraph_core::file::{Plugin, PluginError, Slots};
use rgraph_core::{PassBuilder, PassKind, TextureHandle};

use crate::common::depth::DepthRule;
use crate::common::plugin::Shared;
use crate::common::textures::{self, Input, Want, GBUFFER_INPUTS};
use crate::shaders;

pub struct GBufferResolve(pub(crate) Shared);

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GBufferResolveParams {
    /// Fixes the depth convention; left out, it follows the depth format the compile
    /// picks: reversed-Z for float depth, standard Z for unorm depth.
    #[serde(default)]
    pub reversed_z: Option<bool>,
}

/// The output slots, in the order of [`GBUFFER_INPUTS`] (and of the shader's locations).
const OUTPUTS: [(&str, &str); 4] = [
    ("resolved_albedo", "the resolved albedo"),
    ("resolved_normal", "the resolved normals"),
    ("resolved_material", "the resolved material"),
    ("resolved_view_depth", "the resolved view depth"),
];

/// The resolve as set up: what its `gpu` module records.
#[cfg_attr(not(feature = "gpu"), allow(dead_code))]
pub(crate) struct GBufferResolveDraw {
    pub source: String,
    /// Also gives the clip depth of the far plane, written where no sample has geometry.
    pub depth_rule: DepthRule,
    /// The multisampled G-buffer, group 1.
    pub inputs: Vec<Input>,
    /// albedo, normal, material, view_depth: color attachments 0 to 3.
    pub targets: Vec<TextureHandle>,
    pub depth: TextureHandle,
}

impl Plugin for GBufferResolve {
    const NAME: &'static str = "gbuffer_resolve";
    type Params = GBufferResolveParams;

    fn kind(&self, _: &GBufferResolveParams) -> PassKind {
        PassKind::Render
    }

    fn setup(
        &self,
        params: GBufferResolveParams,
        pass: &mut PassBuilder<'_>,
        slots: &mut Slots<'_>,
    ) -> Result<(), PluginError> {
        let depth_rule = DepthRule::new(params.reversed_z);
        let mut inputs = Vec::new();
        let mut samples = None;
        for (slot, what, formats, binding) in GBUFFER_INPUTS {
            let want = Want {
                samples,
                ..Want::new(what, formats)
            };
            let (input, desc) = textures::sampled(slots, pass, slot, want, binding)?;
            samples = Some(desc.samples);
            inputs.push(input);
        }
        let samples = samples.unwrap_or(1);
        let want = Want::new("the resolved depth-stencil", textures::DEPTH_STENCIL).samples(1);
        let (depth, _) = textures::output(slots, pass, "depth", want, |pass, h, _| {
            depth_rule.start(pass, h)
        })?;
        let mut targets = Vec::new();
        for ((slot, what), (_, _, formats, _)) in OUTPUTS.into_iter().zip(GBUFFER_INPUTS) {
            let want = Want::new(what, formats).samples(1);
            targets.push(textures::color_output(slots, pass, slot, want, [0.0; 4])?.0);
        }
        let draw = GBufferResolveDraw {
            source: shaders::GBUFFER_RESOLVE
                .compose(samples)?
                .source()
                .to_owned(),
            depth_rule,
            inputs,
            targets,
            depth,
        };
        self.0.record(pass, draw);
        Ok(())
    }
}

#[cfg(feature = "gpu")]
mod gpu {
    //! Recording the G-buffer resolve: one full-screen triangle writing the four resolved
    //! targets and, through `frag_depth`, the depth.

    use std::sync::Arc;

    use super::GBufferResolveDraw;
    use crate::common::depth::far_depth;
    use crate::common::gpu::{Frame, InputPass, PipelineDesc, Recorded, Recorder, Render};
    use crate::gpu_scene::GpuScene;

    #[derive(Clone, PartialEq)]
    pub(crate) struct Key {
        targets: Vec<wgpu::TextureFormat>,
        depth: wgpu::TextureFormat,
    }

    impl Recorder for GBufferResolveDraw {
        type Stage = Render;
        // The camera turns the averaged view depth into depth.
        type Scene = Arc<GpuScene>;
        type State = InputPass<Key>;

        fn build(&self, frame: &Frame<'_, '_, Self>) -> Result<Self::State, String> {
            let (label, scene) = ("gbuffer resolve", Some(&*frame.scene));
            Ok(InputPass::new(
                frame.resources,
                label,
                &self.source,
                scene,
                &self.inputs,
            ))
        }

        fn record(&self, state: &mut Self::State, frame: &mut Frame<'_, '_, Self>) -> Recorded {
            let pass = &mut *frame.pass;
            let resources = frame.resources;
            let key = Key {
                targets: self
                    .targets
                    .iter()
                    .map(|&h| resources.shape(h).format)
                    .collect(),
                depth: resources.shape(self.depth).format,
            };
            let convention = self.depth_rule.convention(key.depth);
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
                .build(frame.device)
            });
            pass.set_pipeline(pipeline);
            pass.set_bind_group(0, frame.scene.bind_group(convention), &[]);
            pass.set_bind_group(1, &state.inputs.bind_group(resources), &[]);
            pass.draw(0..3, 0..1);
            Ok(())
        }
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
}
