//! `keys_depth`: a compute rasteriser's visibility buffer (`visibility_compute`'s keys)
//! as a multisampled depth buffer, for the passes that test against the opaque scene's
//! depth: the transparent pass, which the compute raster's pipelines run for scenes
//! with alpha BLEND.
//!
//! ```ron
//! (name: "keys depth", plugin: "keys_depth",
//!  params: (extent: blended),          // or `full` (the default)
//!  inputs: { "samples": "samples" },   // Buffer(per_sample: 8, samples: N)
//!  outputs: { "depth": "depth" })      // depth32float (or depth32float-stencil8), N samples
//! ```
//!
//! A full-screen draw shaded once per sample (its fragment shader reads `sample_index`),
//! each invocation writing its sample's depth from the key through `frag_depth`, with
//! the depth test always passing: the key's high word is the reversed-Z clip depth the
//! rasteriser interpolated at the sample (0, the far depth, where nothing was drawn), so
//! a float depth format holds it exactly and passes reading the buffer take reversed-Z,
//! as they do for a float depth buffer without a `reversed_z` parameter.
//!
//! The buffer is loaded, never cleared (stencil too, where the format has one: nothing
//! tests it): the draw writes every sample the transparent pass can test, and what it
//! leaves is never read. A clear of a multisampled target goes through the ROPs, which on
//! the H200 cost as much as a full-screen pass (2.37 of this pass's 2.40 ms on
//! FlightHelmet at 3840x2160 4x, docs/design/compute-raster.md, run visibility-merged).
//!
//! With `extent: blended` the draw covers only the pixels the scene's blended meshes may
//! cover (the bounds of their world boxes on screen, [`GpuScene::blended_rect`]), and
//! none when none is in view; elsewhere the depth is whatever the texture held. For a
//! depth buffer only the transparent pass reads: shaded once per sample, the draw costs
//! as much as a 4x raster pass's sample writes (5.2 ms of FlightHelmet's 13.1 at 2160p on
//! the H200, docs/design/compute-raster.md, run visibility-tile-raster), where the blended meshes may
//! cover a small part of the output.
//!
//! [`GpuScene::blended_rect`]: crate::gpu_scene::GpuScene::blended_rect

use serde::Deserialize;

use rgraph_core::file::{Plugin, PluginError, Slots};
use rgraph_core::{BufferHandle, PassBuilder, PassKind, TextureHandle};

use crate::common::depth;
use crate::common::extent::Extent;
use crate::common::plugin::Shared;
use crate::common::textures::{self, Want};
use crate::common::visibility_samples;
use crate::shaders;

pub struct KeysDepth(pub(crate) Shared);

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct KeysDepthParams {
    /// Which pixels the depth is written at.
    #[serde(default)]
    pub extent: Extent,
}

/// The draw as set up: what its `gpu` module records.
#[cfg_attr(not(feature = "gpu"), allow(dead_code))]
struct KeysDepthDraw {
    source: String,
    keys: BufferHandle,
    depth: TextureHandle,
    samples: u32,
    extent: Extent,
}

impl Plugin for KeysDepth {
    const NAME: &'static str = "keys_depth";
    type Params = KeysDepthParams;

    fn kind(&self, _: &KeysDepthParams) -> PassKind {
        PassKind::Render
    }

    fn setup(
        &self,
        params: KeysDepthParams,
        pass: &mut PassBuilder<'_>,
        slots: &mut Slots<'_>,
    ) -> Result<(), PluginError> {
        let (keys, samples) = visibility_samples::read(pass, slots, "samples")?;
        let want =
            Want::new("the visibility buffer's depth", textures::DEPTH_FLOAT).samples(samples);
        // Overwritten: the draw writes every sample the transparent pass tests (those of
        // the pixels blended meshes may cover); its clear was 2.37 of this pass's 2.40 ms
        // on the H200 (FlightHelmet at 3840x2160 4x).
        let (depth, _) = textures::output(slots, pass, "depth", want, |pass, h, _| {
            depth::overwrite(pass, h)
        })?;
        let draw = KeysDepthDraw {
            source: shaders::KEYS_DEPTH.compose(samples)?.source().to_owned(),
            keys,
            depth,
            samples,
            extent: params.extent,
        };
        self.0.record(pass, draw);
        Ok(())
    }
}

#[cfg(feature = "gpu")]
mod gpu {
    //! Recording: one full-screen triangle, shaded per sample, writing depth only.

    use std::sync::Arc;

    use super::KeysDepthDraw;
    use crate::common::gpu::{
        Frame, GroupBuffers, InputPass, PipelineDesc, Recorded, Recorder, Render,
    };
    use crate::common::visibility_samples::{fits_binding, KEYS_BINDING};
    use crate::gpu_scene::GpuScene;
    use rgraph_scene::DepthConvention;

    impl Recorder for KeysDepthDraw {
        type Stage = Render;
        // The camera's viewport gives the keys' row length.
        type Scene = Arc<GpuScene>;
        type State = InputPass<wgpu::TextureFormat>;

        fn build(&self, frame: &Frame<'_, '_, Self>) -> Result<Self::State, String> {
            let buffers = GroupBuffers {
                read: vec![(KEYS_BINDING, self.keys)],
                owned: Vec::new(),
            };
            Ok(InputPass::with_geometry(
                frame.resources,
                "keys depth",
                &self.source,
                Some(&frame.scene),
                &[],
                &buffers,
                false,
            ))
        }

        fn record(&self, state: &mut Self::State, frame: &mut Frame<'_, '_, Self>) -> Recorded {
            let pass = &mut *frame.pass;
            let resources = frame.resources;
            fits_binding(frame.device, resources.buffer(self.keys))?;
            let format = resources.shape(self.depth).format;
            let (module, layout) = (&state.module, &state.layout);
            let pipeline = state.pipelines.get(format, |&format| {
                PipelineDesc {
                    label: "keys depth",
                    layout,
                    module,
                    vertex: "vs_fullscreen",
                    buffers: &[],
                    fragment: "fs_keys_depth",
                    constants: &[],
                    targets: &[],
                    cull: None,
                    depth_stencil: Some(wgpu::DepthStencilState {
                        format,
                        depth_write_enabled: Some(true),
                        depth_compare: Some(wgpu::CompareFunction::Always),
                        stencil: wgpu::StencilState::default(),
                        bias: Default::default(),
                    }),
                    samples: self.samples,
                    mask: !0,
                }
                .build(frame.device)
            });
            let shape = resources.shape(self.depth);
            let size = (shape.width, shape.height);
            // Nothing blended in view: no blended fragment tests the depth.
            let Some(rect) = self.extent.rect(&frame.scene, size) else {
                return Ok(());
            };
            pass.set_scissor_rect(rect.x, rect.y, rect.width, rect.height);
            pass.set_pipeline(pipeline);
            let camera = frame.scene.bind_group(DepthConvention::ReversedZ);
            pass.set_bind_group(0, camera, &[]);
            pass.set_bind_group(1, &state.inputs.bind_group(resources), &[]);
            pass.draw(0..3, 0..1);
            Ok(())
        }
    }
}
