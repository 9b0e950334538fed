//! `visibility`: draws the host's opaque meshes into a visibility buffer (Burns & Hunt,
//! "The Visibility Buffer", JCGT 2013): per sample only the depth and the ID of the nearest
//! triangle, which `light_tiled` with an `ids` input rebuilds and shades.
//!
//! ```ron
//! (name: "visibility", plugin: "visibility",
//!  params: (reversed_z: true),          // optional, as the G-buffer pass's
//!  outputs: {
//!      "ids": "ids",        // triangle ID + 1 (0: nothing drawn): r32uint, or rg16uint
//!                           // with the low half in red
//!      "depth": "depth",    // depth32float (or a depth-stencil: stencil cleared to 0)
//!  })
//! ```
//!
//! Both with one sample count; `ids` may be left out, for a depth pre-pass (and the
//! depth-only floor of bench/graphs/visibility_cost). 8 bytes per sample with
//! depth32float, where the lean
//! G-buffer takes 16 and the full one 32. The ID is a triangle's position in the scene's
//! index buffer / 3 (the raster pass pulls its vertices from storage, so its vertex index
//! is that position: visibility.wgsl), exact for any triangle count a u32 index buffer
//! holds. `r32uint` where the device multisamples it (adapter-specific format features:
//! NVIDIA and lavapipe do), else `rg16uint`, which WebGPU multisamples, with the 32 bits
//! split: pipelines declare `format: "r32uint", fallback: "rg16uint"`, and `rgraph explain`
//! shows which a device got. Alpha MASK materials discard below the cutoff using their base
//! colour factor and vertex colour alpha, times a base colour texture's alpha read from
//! the scene's texture table (group 3) where the pixel centre's ray meets the triangle, as
//! the compute raster tests it (mask_texture.wgsl). Alpha BLEND meshes are left to the
//! `transparent` pass, as with a G-buffer.

use serde::Deserialize;

use rgraph_core::file::{Plugin, PluginError, Slots};
use rgraph_core::{ColorLoad, PassBuilder, PassKind, TextureHandle};

use crate::common::depth::DepthRule;
use crate::common::plugin::Shared;
use crate::common::textures::{self, Want};
use crate::shaders;

pub struct Visibility(pub(crate) Shared);

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VisibilityParams {
    /// Fixes the depth convention; left out, it follows the depth format.
    #[serde(default)]
    pub reversed_z: Option<bool>,
}

/// The visibility pass as set up: what its `gpu` module records.
#[cfg_attr(not(feature = "gpu"), allow(dead_code))]
pub(crate) struct VisibilityDraw {
    pub source: String,
    pub depth_rule: DepthRule,
    pub ids: Option<TextureHandle>,
    pub depth: TextureHandle,
}

impl Plugin for Visibility {
    const NAME: &'static str = "visibility";
    type Params = VisibilityParams;

    fn kind(&self, _: &VisibilityParams) -> PassKind {
        PassKind::Render
    }

    fn setup(
        &self,
        params: VisibilityParams,
        pass: &mut PassBuilder<'_>,
        slots: &mut Slots<'_>,
    ) -> Result<(), PluginError> {
        let depth_rule = DepthRule::new(params.reversed_z);
        let want = Want::new("the visibility buffer's depth", textures::DEPTH_ANY);
        let (depth, desc) = textures::output(slots, pass, "depth", want, |pass, h, _| {
            depth_rule.start(pass, h)
        })?;
        let ids = match slots.is_output("ids") {
            true => {
                let want = Want::new("the visibility buffer's triangle IDs", textures::IDS)
                    .samples(desc.samples);
                let output = textures::output(slots, pass, "ids", want, |pass, h, _| {
                    pass.color_output(h, ColorLoad::Clear([0.0; 4]))
                })?;
                Some(output.0)
            }
            false => None,
        };
        let draw = VisibilityDraw {
            source: shaders::VISIBILITY
                .compose_with(desc.samples, "")?
                .source()
                .to_owned(),
            depth_rule,
            ids,
            depth,
        };
        self.0.record(pass, draw);
        Ok(())
    }
}

#[cfg(feature = "gpu")]
mod gpu {
    //! Recording the visibility pass: every opaque mesh drawn with its vertices pulled,
    //! a pipeline per culling and alpha-mask state.

    use std::sync::Arc;

    use super::VisibilityDraw;
    use crate::common::gpu::pipeline::{module, pipeline_layout, PipelineDesc, Pipelines};
    use crate::common::gpu::scene_draw::depth_test;
    use crate::common::gpu::{split_ids, Frame, Recorded, Recorder, Render};
    use crate::gpu_scene::{GpuScene, Layer};
    use crate::variant::GatedShader;
    use rgraph_scene::DepthConvention;

    #[derive(Clone, PartialEq)]
    pub(crate) struct Key {
        ids: Option<wgpu::TextureFormat>,
        depth: wgpu::TextureFormat,
        samples: u32,
        convention: DepthConvention,
        masked: bool,
        double_sided: bool,
    }

    pub(crate) struct State {
        module: wgpu::ShaderModule,
        layout: wgpu::PipelineLayout,
        pipelines: Pipelines<Key>,
    }

    impl Recorder for VisibilityDraw {
        type Stage = Render;
        type Scene = Arc<GpuScene>;
        type State = State;

        fn build(&self, frame: &Frame<'_, '_, Self>) -> Result<State, String> {
            let (device, scene) = (frame.device, &frame.scene);
            Ok(State {
                module: module(device, "visibility", &self.source),
                // Group 1 is the light passes' inputs; geometry is group 2 and the texture
                // table group 3 in both.
                layout: pipeline_layout(
                    device,
                    &[
                        Some(scene.layout()),
                        None,
                        Some(scene.geometry_layout()),
                        Some(scene.texture_table_layout()),
                    ],
                ),
                pipelines: Pipelines::default(),
            })
        }

        fn record(&self, state: &mut State, frame: &mut Frame<'_, '_, Self>) -> Recorded {
            let pass = &mut *frame.pass;
            let (resources, device, scene) = (frame.resources, frame.device, &frame.scene);
            let geometry = scene.geometry_group(device)?;
            // Textured alpha masks read the table.
            let table = frame.scenes.texture_table(scene, device, resources.queue)?;
            let variant = frame.scenes.variant(GatedShader::VisibilityRaster);
            let ids = self.ids.map(|ids| resources.shape(ids).format);
            let depth = resources.shape(self.depth);
            let convention = self.depth_rule.convention(depth.format);
            pass.set_bind_group(0, scene.bind_group(convention), &[]);
            pass.set_bind_group(2, geometry, &[]);
            pass.set_bind_group(3, table, &[]);
            scene.pull_meshes(pass, |pass, _, material| {
                let key = Key {
                    ids,
                    depth: depth.format,
                    samples: depth.samples,
                    convention,
                    masked: material.masked,
                    double_sided: material.double_sided,
                };
                let (module, layout) = (&state.module, &state.layout);
                let pipeline = state.pipelines.get(key, |key| {
                    let targets: Vec<Option<wgpu::ColorTargetState>> = key
                        .ids
                        .map(|format| wgpu::ColorTargetState {
                            format,
                            blend: None,
                            write_mask: wgpu::ColorWrites::ALL,
                        })
                        .into_iter()
                        .map(Some)
                        .collect();
                    let mut constants = vec![("SPLIT_IDS", key.ids.map_or(0.0, split_ids))];
                    constants.extend(variant.constants());
                    PipelineDesc {
                        label: "visibility",
                        layout,
                        module,
                        vertex: "vs_visibility",
                        buffers: &[],
                        fragment: match (key.ids.is_some(), key.masked) {
                            (true, true) => "fs_visibility_masked",
                            (true, false) => "fs_visibility",
                            (false, true) => "fs_depth_masked",
                            (false, false) => "fs_depth",
                        },
                        constants: &constants,
                        targets: &targets,
                        cull: (!key.double_sided).then_some(wgpu::Face::Back),
                        depth_stencil: Some(depth_test(
                            key.depth,
                            key.convention,
                            Layer::Opaque,
                            false,
                        )),
                        samples: key.samples,
                        mask: !0,
                    }
                    .build(device)
                });
                pass.set_pipeline(pipeline);
                true
            });
            Ok(())
        }
    }
}
