//! `shadow_resolve`: the shadow atlas the light passes read, from the compute raster's
//! keys (`shadow_raster`) and, where the hardware drew the alpha MASK meshes
//! (`shadow_maps`), the nearer of both at each texel.
//!
//! ```ron
//! (name: "shadow resolve", plugin: "shadow_resolve",
//!  when: "shadows",
//!  params: (cache: true),                 // the default with `previous`: below
//!  inputs: { "keys": "shadow_keys",       // 4 bytes a texel of the atlas
//!            "depth": "shadow_depth",     // optional: depth32float, the atlas's size
//!            "previous": "shadow_atlas_prev" },  // History(of: "shadow_atlas"), with cache
//!  optional: ["depth"],
//!  outputs: { "atlas": "shadow_atlas" })  // r32float, Absolute(N, N)
//! ```
//!
//! With `cache`, a frame whose shadow work has the stamp of the last one drawn copies
//! `previous`, the last frame's atlas, and reads no key: `shadow_raster` drew nothing
//! (common/shadow_cache.rs).
//!
//! A compute pass, an invocation a texel, which stores the atlas rather than drawing it:
//! no depth format is a storage texture, and the hardware's depth writes are what the
//! compute raster replaces (on an H100 they took 2 to 3 ms for a 4096-texel atlas;
//! docs/design/shadows.md). The light passes read either format alike
//! (common/shadows.rs).

use serde::Deserialize;

use rgraph_core::file::{Plugin, PluginError, Slots};
use rgraph_core::types::TextureFormat;
use rgraph_core::{BufferHandle, PassBuilder, PassKind, Size, TextureHandle};

use crate::common::plugin::Shared;
use crate::common::shadow_cache;
use crate::common::shadow_depth::{check_atlas, keys};
use crate::common::switch::Switch;
use crate::common::textures::{self, Want};
use crate::shaders;

pub struct ShadowResolve(pub(crate) Shared);

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ShadowResolveParams {
    /// Whether the last frame's atlas is copied while nothing it shows moved, as
    /// `shadow_raster`'s `cache`: by default where the file gives a `previous` input.
    #[serde(default)]
    pub cache: Option<Switch>,
}

/// The pass as set up: what its `gpu` module records.
#[cfg_attr(not(feature = "gpu"), allow(dead_code))]
pub(crate) struct ShadowResolveDispatch {
    pub source: String,
    pub keys: BufferHandle,
    /// The hardware's depth of the alpha MASK meshes, where the file gives it (an
    /// optional read: dropped in scenes without them).
    pub depth: Option<TextureHandle>,
    pub atlas: TextureHandle,
    /// The last frame's atlas, copied where it is kept.
    pub previous: Option<TextureHandle>,
}

impl Plugin for ShadowResolve {
    const NAME: &'static str = "shadow_resolve";
    type Params = ShadowResolveParams;

    fn kind(&self, _: &ShadowResolveParams) -> PassKind {
        PassKind::Compute
    }

    fn setup(
        &self,
        params: ShadowResolveParams,
        pass: &mut PassBuilder<'_>,
        slots: &mut Slots<'_>,
    ) -> Result<(), PluginError> {
        let want = Want::new("the shadow atlas", &[TextureFormat::R32Float]).samples(1);
        let (atlas, desc) = textures::output(slots, pass, "atlas", want, |pass, h, _| {
            pass.storage_write(h)
        })?;
        check_atlas(slots, "atlas", desc.size)?;
        let keys = keys(pass, slots, desc.size)?;
        let depth = match slots.kind("depth") {
            Some(_) => Some(depth(pass, slots, desc.size)?),
            None => None,
        };
        let previous = shadow_cache::previous(params.cache, pass, slots)?;
        let dispatch = ShadowResolveDispatch {
            source: shaders::SHADOW_RESOLVE.compose(1)?.source().to_owned(),
            keys,
            depth,
            atlas,
            previous,
        };
        self.0.record(pass, dispatch);
        Ok(())
    }
}

/// Takes the `depth` input, checked to be the hardware's depth the atlas's `size`.
fn depth(
    pass: &mut PassBuilder<'_>,
    slots: &mut Slots<'_>,
    size: Size,
) -> Result<TextureHandle, PluginError> {
    let want = Want::new("the shadow maps' depth", &[TextureFormat::Depth32Float]).samples(1);
    let (depth, desc) = textures::input(slots, pass, "depth", want)?;
    if desc.size != size {
        return Err(PluginError::Slot {
            slot: "depth".to_owned(),
            resource: slots.resource("depth").unwrap_or("depth").to_owned(),
            why: format!(
                "is {:?}, but it must be the atlas's size, {size:?}",
                desc.size
            ),
        });
    }
    Ok(pass.sampled(depth))
}

#[cfg(feature = "gpu")]
mod gpu {
    //! Recording: the pipeline with the depth, without it, or copying the kept atlas,
    //! as the plan and the frame give it, each made the first time it records.

    use std::sync::Arc;

    use super::ShadowResolveDispatch;
    use crate::common::gpu::bindings::TextureBindings;
    use crate::common::gpu::pipeline::{module, pipeline_layout};
    use crate::common::gpu::shadow_cache::Kept;
    use crate::common::gpu::{compute_pipeline, Compute, Frame, Recorded, Recorder};
    use crate::common::textures::{Input, Texels};
    use crate::gpu_scene::GpuScene;
    use rgraph_core::Aspect;

    /// A variant's bindings and pipeline.
    pub(crate) struct Variant {
        bindings: TextureBindings,
        pipeline: wgpu::ComputePipeline,
    }

    pub(crate) struct State {
        /// From the keys, from the keys and the depth, and the kept atlas copied.
        variants: [Option<Variant>; 3],
        kept: Kept,
    }

    impl Recorder for ShadowResolveDispatch {
        type Stage = Compute;
        // The frame's shadow work, whose stamp says whether the atlas is kept.
        type Scene = Arc<GpuScene>;
        type State = State;

        fn build(&self, _: &Frame<'_, '_, Self>) -> Result<State, String> {
            Ok(State {
                variants: [None, None, None],
                kept: Kept::default(),
            })
        }

        fn record(&self, state: &mut State, frame: &mut Frame<'_, '_, Self>) -> Recorded {
            let resources = frame.resources;
            let side = resources.shape(self.atlas).width;
            let work = frame
                .scene
                .compute_shadow_work(resources.output_size(), side);
            let kept = match (self.previous, work) {
                (Some(previous), Some(work)) => {
                    state.kept.keeps(&work, resources.history_reset(previous))
                }
                _ => false,
            };
            let depth = self.depth.filter(|d| resources.has(*d));
            let (index, entry) = match (kept, depth) {
                (true, _) => (2, "cs_keep"),
                (false, None) => (0, "cs_resolve_keys"),
                (false, Some(_)) => (1, "cs_resolve_both"),
            };
            let variant = state.variants[index].get_or_insert_with(|| {
                let mut inputs = vec![Input {
                    binding: 2,
                    texture: self.atlas,
                    aspect: Aspect::All,
                    texels: Texels::Store,
                }];
                let read = |binding, texture| Input {
                    binding,
                    texture,
                    aspect: Aspect::All,
                    texels: Texels::Float,
                };
                let keys: &[_] = match kept {
                    true => {
                        inputs.extend(self.previous.map(|texture| read(3, texture)));
                        &[]
                    }
                    false => {
                        inputs.extend(depth.map(|texture| read(1, texture)));
                        &[(0, self.keys)]
                    }
                };
                let bindings = TextureBindings::with_buffers(resources, &inputs, keys, &[]);
                let device = frame.device;
                let layout = pipeline_layout(device, &[Some(&bindings.layout)]);
                let module = module(device, "shadow resolve", &self.source);
                let pipeline =
                    compute_pipeline(device, "shadow resolve", &layout, &module, entry, &[]);
                Variant { bindings, pipeline }
            });
            let pass = &mut *frame.pass;
            pass.set_pipeline(&variant.pipeline);
            pass.set_bind_group(0, &variant.bindings.bind_group(resources), &[]);
            pass.dispatch_workgroups(side.div_ceil(8), side.div_ceil(8), 1);
            Ok(())
        }
    }
}
