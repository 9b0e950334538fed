//! `shadow_resolve`: the shadow atlas the light passes read, from the compute raster's
//! keys (`shadow_raster`) and, where the hardware drew the alpha MASK meshes
//! (`shadow_maps`), the nearer of both at each texel.
//!
//! ```ron
//! (name: "shadow resolve", plugin: "shadow_resolve",
//!  when: "shadows",
//!  inputs: { "keys": "shadow_keys",       // 4 bytes a texel of the atlas
//!            "depth": "shadow_depth" },   // optional: depth32float, the atlas's size
//!  optional: ["depth"],
//!  outputs: { "atlas": "shadow_atlas" })  // r32float, Absolute(N, N)
//! ```
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
use crate::common::shadow_depth::{check_atlas, keys};
use crate::common::textures::{self, Want};
use crate::shaders;

pub struct ShadowResolve(pub(crate) Shared);

#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ShadowResolveParams {}

/// The pass as set up: what its `gpu` module records.
#[cfg_attr(not(feature = "gpu"), allow(dead_code))]
pub(crate) struct ShadowResolveDispatch {
    pub source: String,
    pub keys: BufferHandle,
    /// The hardware's depth of the alpha MASK meshes, where the file gives it (an
    /// optional read: dropped in scenes without them).
    pub depth: Option<TextureHandle>,
    pub atlas: TextureHandle,
}

impl Plugin for ShadowResolve {
    const NAME: &'static str = "shadow_resolve";
    type Params = ShadowResolveParams;

    fn kind(&self, _: &ShadowResolveParams) -> PassKind {
        PassKind::Compute
    }

    fn setup(
        &self,
        _: ShadowResolveParams,
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
        let dispatch = ShadowResolveDispatch {
            source: shaders::SHADOW_RESOLVE.compose(1)?.source().to_owned(),
            keys,
            depth,
            atlas,
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
    //! Recording: the pipeline with the depth or without, as the plan gives it, each
    //! made the first time it records.

    use super::ShadowResolveDispatch;
    use crate::common::gpu::bindings::TextureBindings;
    use crate::common::gpu::pipeline::{module, pipeline_layout};
    use crate::common::gpu::{compute_pipeline, Compute, Frame, Recorded, Recorder};
    use crate::common::textures::{Input, Texels};
    use rgraph_core::Aspect;

    /// A variant's bindings and pipeline.
    pub(crate) struct Variant {
        bindings: TextureBindings,
        pipeline: wgpu::ComputePipeline,
    }

    impl Recorder for ShadowResolveDispatch {
        type Stage = Compute;
        type Scene = ();
        /// Without the depth, and with it.
        type State = [Option<Variant>; 2];

        fn reads_scene(&self) -> bool {
            false
        }

        fn build(&self, _: &Frame<'_, '_, Self>) -> Result<Self::State, String> {
            Ok([None, None])
        }

        fn record(&self, state: &mut Self::State, frame: &mut Frame<'_, '_, Self>) -> Recorded {
            let resources = frame.resources;
            let depth = self.depth.filter(|d| resources.has(*d));
            let (index, entry) = match depth {
                None => (0, "cs_resolve_keys"),
                Some(_) => (1, "cs_resolve_both"),
            };
            let variant = state[index].get_or_insert_with(|| {
                let mut inputs = vec![Input {
                    binding: 2,
                    texture: self.atlas,
                    aspect: Aspect::All,
                    texels: Texels::Store,
                }];
                inputs.extend(depth.map(|texture| Input {
                    binding: 1,
                    texture,
                    aspect: Aspect::All,
                    texels: Texels::Float,
                }));
                let keys = [(0, self.keys)];
                let bindings = TextureBindings::with_buffers(resources, &inputs, &keys, &[]);
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
            let side = resources.shape(self.atlas).width;
            pass.dispatch_workgroups(side.div_ceil(8), side.div_ceil(8), 1);
            Ok(())
        }
    }
}
