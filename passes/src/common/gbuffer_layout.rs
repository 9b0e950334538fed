//! The G-buffers a lighting pass can read, told apart by the slots its file binds: the
//! full one (`view_depth` and `hdr`), the lean one (neither; `emission` when the scene
//! emits), a mix, or a visibility buffer (`ids`: a raster pass's triangle IDs beside its
//! `depth`, or `samples`: a compute rasteriser's buffer of depth and ID per sample), whose
//! triangles the pass rebuilds. For each, the textures to bind (group 1) and the WGSL
//! that reads them (gbuffer_read.wgsl or visibility_read.wgsl, a `load_view_depth`, an
//! `emitted`, and a G-buffer's `load_layers` for the material layers it holds:
//! common/gbuffer_layers.rs), so the rest of the pass's shader is one source for all of
//! them.

use rgraph_core::file::{PluginError, Slots};
use rgraph_core::{Aspect, PassBuilder, TextureHandle};

use crate::common::gbuffer_layers::{self, LayerSet, LayerTargets};
use crate::common::textures::{self, Input, Texels, Want, GBUFFER_INPUTS};
use crate::layers::Layer;
use crate::shaders;

/// Which G-buffer a pass reads (see the module documentation).
pub(crate) struct GBufferLayout {
    pub surfaces: Surfaces,
    pub stored_view_depth: bool,
    emitted: Emitted,
}

/// Where a pass finds its samples' surfaces.
#[derive(Copy, Clone, PartialEq, Eq)]
pub(crate) enum Surfaces {
    /// A G-buffer's channels, and its depth buffer.
    GBuffer,
    /// A raster pass's visibility buffer: `ids` and the depth buffer.
    VisibilityTextures,
    /// A compute rasteriser's visibility buffer, `samples` (common/visibility_samples.rs):
    /// no depth buffer.
    VisibilitySamples,
}

impl Surfaces {
    /// Rebuilt from triangle IDs.
    pub fn visibility(self) -> bool {
        self != Surfaces::GBuffer
    }
}

enum Emitted {
    /// `hdr` or `emission`.
    Channel(&'static str),
    /// No channel: what the surface carries (a visibility buffer's emission), unlit colour
    /// from albedo, this background elsewhere.
    Surface([f64; 3]),
}

impl GBufferLayout {
    /// The layout of the slots `slots` lists; `background` is what samples where nothing
    /// was drawn resolve to without an `hdr` or `emission` channel.
    pub fn of(
        slots: &Slots<'_>,
        background: Option<[f64; 3]>,
    ) -> Result<GBufferLayout, PluginError> {
        let listed = |slot| slots.kind(slot).is_some();
        let emitted = match (listed("hdr"), listed("emission"), background) {
            (true, true, _) => {
                return Err(PluginError::Invalid(
                    "inputs \"hdr\" and \"emission\" both hold what samples emit: bind one".into(),
                ))
            }
            (true, false, Some(_)) | (false, true, Some(_)) => {
                return Err(PluginError::Invalid(
                    "background is for a G-buffer without \"hdr\" or \"emission\": with one, the \
                     background is what the G-buffer pass cleared it to"
                        .into(),
                ))
            }
            (true, false, None) => Emitted::Channel("hdr"),
            (false, true, None) => Emitted::Channel("emission"),
            (false, false, background) => {
                let background = background.unwrap_or([0.0; 3]);
                if !background.iter().all(|c| c.is_finite() && *c >= 0.0) {
                    return Err(PluginError::Invalid(format!(
                        "background must be finite and not negative, got {background:?}"
                    )));
                }
                Emitted::Surface(background)
            }
        };
        let surfaces = match (listed("ids"), listed("samples")) {
            (true, true) => {
                return Err(PluginError::Invalid(
                    "inputs \"ids\" and \"samples\" are two visibility buffers: bind one".into(),
                ))
            }
            (true, false) => Surfaces::VisibilityTextures,
            (false, true) => Surfaces::VisibilitySamples,
            (false, false) => Surfaces::GBuffer,
        };
        if surfaces.visibility() {
            let gbuffer = [
                "albedo",
                "normal",
                "material",
                "view_depth",
                "hdr",
                "emission",
            ];
            if let Some(slot) = gbuffer
                .into_iter()
                .chain(Layer::ALL.map(Layer::slot))
                .find(|&slot| listed(slot))
            {
                return Err(PluginError::Invalid(format!(
                    "a visibility buffer's input and \"{slot}\" (a G-buffer's) are two ways \
                     of reading the surfaces: bind one"
                )));
            }
        }
        Ok(GBufferLayout {
            surfaces,
            stored_view_depth: listed("view_depth"),
            emitted,
        })
    }

    /// The shader fragments that read this layout, a G-buffer with the material layers of
    /// `layers` (a visibility buffer rebuilds every layer from the material table).
    pub fn wgsl(&self, layers: LayerSet) -> String {
        let reader = match self.surfaces {
            Surfaces::GBuffer => shaders::GBUFFER_READ,
            Surfaces::VisibilityTextures => shaders::VISIBILITY_READ_TEXTURES,
            Surfaces::VisibilitySamples => shaders::VISIBILITY_READ_SAMPLES,
        };
        let view_depth = match self.stored_view_depth {
            true => shaders::VIEW_DEPTH_STORED,
            false => shaders::VIEW_DEPTH_FROM_DEPTH,
        };
        let emitted = match self.emitted {
            Emitted::Channel("hdr") => shaders::EMITTED_HDR.to_owned(),
            Emitted::Channel(_) => shaders::EMITTED_RGB9E5.to_owned(),
            Emitted::Surface([r, g, b]) => format!(
                "const BACKGROUND: vec3<f32> = vec3<f32>({r:?}, {g:?}, {b:?});\n{}",
                shaders::EMITTED_SURFACE
            ),
        };
        let layers = match self.surfaces {
            Surfaces::GBuffer => gbuffer_layers::read_wgsl(layers),
            Surfaces::VisibilityTextures | Surfaces::VisibilitySamples => String::new(),
        };
        format!("{reader}\n{view_depth}\n{emitted}\n{layers}")
    }

    /// Declares the layout's textures sampled and adds them to `inputs` at
    /// gbuffer_read.wgsl's and visibility_textures.wgsl's bindings, each checked to have
    /// `samples`. Returns a raster pass's visibility buffer's IDs, if it is one (a
    /// compute rasteriser's buffer is the pass's own to bind: it is no texture), and a
    /// G-buffer's material-layer targets the file lists.
    pub fn bind(
        &self,
        slots: &mut Slots<'_>,
        pass: &mut PassBuilder<'_>,
        samples: u32,
        inputs: &mut Vec<Input>,
    ) -> Result<(Option<TextureHandle>, LayerTargets), PluginError> {
        let mut sampled = |slot, what, formats, binding, texels| {
            let want = Want::new(what, formats).samples(samples);
            let (handle, _) = textures::input(slots, pass, slot, want)?;
            pass.sampled(handle);
            inputs.push(Input {
                binding,
                texture: handle,
                aspect: Aspect::All,
                texels,
            });
            Ok::<_, PluginError>(handle)
        };
        if self.surfaces == Surfaces::VisibilitySamples {
            return Ok((None, Vec::new()));
        }
        if self.surfaces == Surfaces::VisibilityTextures {
            let what = "the visibility buffer's triangle IDs";
            let ids = sampled("ids", what, textures::IDS, 0, Texels::Uint)?;
            return Ok((Some(ids), Vec::new()));
        }
        for (slot, what, formats, binding) in GBUFFER_INPUTS {
            if slot != "view_depth" || self.stored_view_depth {
                sampled(slot, what, formats, binding, Texels::Float)?;
            }
        }
        match self.emitted {
            Emitted::Channel("hdr") => {
                sampled(
                    "hdr",
                    "the G-buffer's HDR target",
                    textures::HDR,
                    6,
                    Texels::Float,
                )?;
            }
            Emitted::Channel(slot) => {
                sampled(
                    slot,
                    "the G-buffer's emission",
                    textures::EMISSION,
                    6,
                    Texels::Uint,
                )?;
            }
            Emitted::Surface(_) => {}
        }
        let layers = gbuffer_layers::inputs(slots, pass, samples, inputs)?;
        Ok((None, layers))
    }
}
