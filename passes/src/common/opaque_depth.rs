//! The opaque scene's depth as a pass after the opaque passes reads it, from either kind of
//! pipeline: a depth buffer's depth aspect (slot `depth`, any depth format and sample
//! count, in its convention) or a compute rasteriser's keys (slot `samples`: reversed-Z,
//! 0 where nothing was drawn). The pass's shader gets the same functions either way
//! ([`OpaqueDepth::wgsl`]): `sample_depth_at(pixel, s)`, a sample's clip depth (the
//! convention's FAR_DEPTH where nothing was drawn), `one_surface(pixel)`, whether sample
//! 0 speaks for every sample of the pixel (the keys say so where a pixel shows one
//! triangle; a depth buffer does not, so every sample is read), and `coverage_size()`,
//! the pixels they cover. The particles' depth downsample and the background read it.

use rgraph_core::file::{PluginError, Slots};
use rgraph_core::{Aspect, BufferHandle, PassBuilder};

use super::depth::DepthRule;
use super::textures::{self, Input, Texels, Want};
use super::visibility_samples;
use crate::shaders;

/// Where the opaque depth is read: see the module documentation.
#[derive(Copy, Clone, Debug)]
#[cfg_attr(not(feature = "gpu"), allow(dead_code))]
pub(crate) enum OpaqueDepth {
    /// A depth buffer at group 1 binding 0, in the convention the rule gives its format.
    Buffer(Input, DepthRule),
    /// A compute rasteriser's keys (group 1, visibility_samples.wgsl's binding).
    Keys(BufferHandle),
}

impl OpaqueDepth {
    /// Reads slot `samples` where the file gives it, else slot `depth` (whose convention
    /// `reversed_z` fixes, or its format); with the samples per pixel.
    pub fn read(
        slots: &mut Slots<'_>,
        pass: &mut PassBuilder<'_>,
        reversed_z: Option<bool>,
    ) -> Result<(OpaqueDepth, u32), PluginError> {
        if slots.kind("samples").is_some() {
            let (keys, samples) = visibility_samples::read(pass, slots, "samples")?;
            return Ok((OpaqueDepth::Keys(keys), samples));
        }
        let want = Want::new("the opaque passes' depth", textures::DEPTH_ANY);
        let (depth, desc) = textures::input(slots, pass, "depth", want)?;
        pass.sampled_aspect(depth, Aspect::DepthOnly);
        let input = Input {
            binding: 0,
            texture: depth,
            aspect: Aspect::DepthOnly,
            texels: Texels::Depth,
        };
        Ok((
            OpaqueDepth::Buffer(input, DepthRule::new(reversed_z)),
            desc.samples,
        ))
    }

    /// The WGSL defining the functions the module documentation names, with the
    /// bindings they read; after common.wgsl and scene.wgsl.
    pub fn wgsl(&self) -> String {
        match self {
            OpaqueDepth::Keys(_) => format!(
                "{}\nfn sample_depth_at(pixel: vec2<i32>, s: u32) -> f32 {{\n    \
                 return sample_depth(pixel, s);\n}}\n\
                 fn coverage_size() -> vec2<f32> {{\n    return camera.viewport;\n}}\n",
                shaders::KEYS
            ),
            OpaqueDepth::Buffer(..) => "@group(1) @binding(0) var scene_depth: GTexD;\n\
                 fn sample_depth_at(pixel: vec2<i32>, s: u32) -> f32 {\n    \
                 return textureLoad(scene_depth, pixel, s);\n}\n\
                 fn one_surface(pixel: vec2<i32>) -> bool {\n    return false;\n}\n\
                 fn coverage_size() -> vec2<f32> {\n    \
                 return vec2<f32>(textureDimensions(scene_depth));\n}\n"
                .to_owned(),
        }
    }
}

#[cfg(feature = "gpu")]
mod gpu {
    use rgraph_core::gpu::FrameResources;

    use super::OpaqueDepth;
    use crate::common::gpu::GroupBuffers;
    use crate::common::textures::Input;
    use crate::common::visibility_samples::{fits_binding, KEYS_BINDING};
    use rgraph_scene::DepthConvention;

    /// What a pass binds for an [`OpaqueDepth`] in group 1, and the convention its values
    /// (and the camera unprojecting them) follow.
    pub(crate) struct Bound {
        pub inputs: Vec<Input>,
        pub buffers: GroupBuffers,
        pub convention: DepthConvention,
    }

    impl OpaqueDepth {
        /// What a pass binds in group 1: its own `inputs`, then `depth`'s bindings where it
        /// reads one; the convention its camera follows (reversed-Z without a depth).
        pub fn bound_with(
            depth: Option<&OpaqueDepth>,
            inputs: &[Input],
            resources: &FrameResources<'_>,
        ) -> Result<Bound, String> {
            let mut bound = match depth {
                Some(depth) => depth.bound(resources)?,
                None => Bound {
                    inputs: Vec::new(),
                    buffers: GroupBuffers::default(),
                    convention: DepthConvention::ReversedZ,
                },
            };
            bound.inputs.splice(0..0, inputs.iter().copied());
            Ok(bound)
        }

        /// Its bindings as the plan shapes them, or why the device cannot bind the keys.
        pub fn bound(&self, resources: &FrameResources<'_>) -> Result<Bound, String> {
            Ok(match *self {
                OpaqueDepth::Buffer(input, rule) => Bound {
                    inputs: vec![input],
                    buffers: GroupBuffers::default(),
                    convention: rule.convention(resources.shape(input.texture).format),
                },
                OpaqueDepth::Keys(keys) => {
                    fits_binding(resources.device, resources.buffer(keys))?;
                    Bound {
                        inputs: Vec::new(),
                        buffers: GroupBuffers {
                            read: vec![(KEYS_BINDING, keys)],
                            owned: Vec::new(),
                        },
                        convention: DepthConvention::ReversedZ,
                    }
                }
            })
        }
    }
}
