//! The light passes' optional `ao` input: screen-space ambient occlusion (passes/ssao.rs)
//! that darkens the ambient and environment light only (seed 004: occlusion of light
//! from everywhere, not a shadow of the direct lights). Without the slot the generated
//! WGSL leaves the surface as it is, so the shader compiles it out and the image is the
//! one the pass draws without SSAO, bit for bit.

use rgraph_core::file::{PluginError, Slots};
use rgraph_core::types::TextureFormat;
use rgraph_core::PassBuilder;

use super::textures::{self, Input, Want};

/// The occlusion SSAO writes: one channel, 1 unoccluded.
pub(crate) const AO: &[TextureFormat] = &[TextureFormat::R8Unorm];

/// Where the light passes bind it (group 1): after gbuffer_read.wgsl's bindings (0 to 5)
/// and light_tiled.wgsl's (6 and 7).
const BINDING: u32 = 8;

/// The `ao` slot when the file gives one: declared sampled, bound at [`BINDING`].
pub(crate) fn input(
    slots: &mut Slots<'_>,
    pass: &mut PassBuilder<'_>,
) -> Result<Option<Input>, PluginError> {
    if slots.kind("ao").is_none() {
        return Ok(None);
    }
    let want = Want::new("the screen-space ambient occlusion", AO).samples(1);
    Ok(Some(textures::sampled(slots, pass, "ao", want, BINDING)?.0))
}

/// The WGSL for [`input`]'s result, composed after the light shader:
/// `with_screen_ao(surface, pixel)`, the surface with its occlusion (which scales only
/// `ambient_light`, lighting.wgsl) multiplied by the pixel's AO.
pub(crate) fn wgsl(input: Option<&Input>) -> String {
    match input {
        Some(input) => format!(
            "// Generated: the ao input (common/ao.rs).\n\
             @group(1) @binding({}) var screen_ao_tex: texture_2d<f32>;\n\
             fn with_screen_ao(s: Surface, pixel: vec2<i32>) -> Surface {{\n    \
                 var t = s;\n    \
                 t.occlusion *= textureLoad(screen_ao_tex, pixel, 0).r;\n    \
                 return t;\n\
             }}\n",
            input.binding
        ),
        None => "// Generated: no ao input (common/ao.rs).\n\
                 fn with_screen_ao(s: Surface, pixel: vec2<i32>) -> Surface {\n    \
                     return s;\n\
                 }\n"
        .to_owned(),
    }
}
