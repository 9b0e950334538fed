//! `forward`: draws the host's scene straight into a (multisampled) HDR target, every
//! light evaluated per fragment: what users pick instead of deferred + MSAA, and the image
//! MSAA should give. The baselines and the supersampled reference are built on it.
//!
//! ```ron
//! (name: "forward", plugin: "forward",
//!  params: (shading: pixel,          // the default; or sample (one invocation per sample)
//!           background: (0.0, 0.0, 0.0, 1.0)),   // these defaults; reversed_z optional
//!  outputs: {
//!      "hdr": "hdr",       // rgba16float, the depth's sample count
//!      "depth": "depth",   // depth24plus(-stencil8) or depth32float(-stencil8)
//!  },
//!  inputs: { "shadows": "shadow_atlas" })   // optional: shadow_maps's atlas, which
//!                                           // scales each shadowed light (group 2)
//! ```
//!
//! Shading is brdf.wgsl's, as in the deferred light passes: Lambert plus GGX
//! metallic-roughness, the ambient term times albedo, and every directional, point and spot
//! light of the scene (point and spot lights windowed to zero at their range, which the
//! deferred passes' volumes circumscribe). Emission is added once; unlit materials show
//! base color plus emission, exactly what the `gbuffer` pass writes into its HDR target.
//! Alpha MASK and double-sided materials behave as there; alpha BLEND meshes are left to
//! the `transparent` pass, as the G-buffer pass leaves them. The HDR target is not
//! cleared: after the meshes, the samples none drew are filled with `background`
//! (common/background.rs), as the G-buffer pass fills its targets.
//!
//! `pixel` shades once per pixel and triangle at the centroid of the covered samples (the
//! G-buffer pass's interpolation, so a deferred pipeline that shades every sample gives the
//! same image); `sample` shades every covered sample at its own position
//! (`@interpolate(sample)`), which is supersampling: the reference uses it.
//!
//! `view: shadows` or `view: cascades` draws a debug view of the shadow maps instead of
//! the lit colour, once per pixel, into a displayable target (rgba8unorm(-srgb)): the most
//! important shadowed light's visibility term, or the sun's cascade at each fragment,
//! darker in its shadow, as `light_tiled`'s views draw them from a G-buffer
//! (shadow_debug.wgsl); grey where the material is unlit, black where nothing is drawn.
//! Its `shadows` input is then required: `forward_msaa_4x.ron`'s `--view shadows`.

use serde::Deserialize;

use rgraph_core::file::{Plugin, PluginError, Slots};
use rgraph_core::types::TextureFormat;
use rgraph_core::{PassBuilder, PassKind};

use super::gbuffer::opaque_black;
use crate::common::background::FilledTargets;
use crate::common::depth::DepthRule;
use crate::common::plugin::Shared;
use crate::common::scene_draw::{Masked, SceneDraw, Stages};
use crate::common::shadows;
use crate::common::textures::{self, Want};
use crate::shaders;
use crate::variant::GatedShader;

pub struct Forward(pub(crate) Shared);

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ForwardParams {
    #[serde(default)]
    pub shading: Shading,
    /// Fixes the depth convention; left out, it follows the depth format the compile
    /// picks: reversed-Z for float depth, standard Z for unorm depth.
    #[serde(default)]
    pub reversed_z: Option<bool>,
    /// The HDR target's value where no geometry is drawn (linear RGBA).
    #[serde(default = "opaque_black")]
    pub background: [f64; 4],
    /// What the pass draws: the lit colour, or a debug view of the shadow maps.
    #[serde(default)]
    pub view: View,
}

/// What `forward` draws.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum View {
    /// The lit colour.
    #[default]
    Shaded,
    /// The most important shadowed light's visibility term, white where lit.
    Shadows,
    /// The sun's cascade at each fragment, darker in its shadow.
    Cascades,
}

impl View {
    /// The view's name in a file, where it draws the shadow maps.
    fn of_shadow_maps(self) -> Option<&'static str> {
        match self {
            View::Shaded => None,
            View::Shadows => Some("shadows"),
            View::Cascades => Some("cascades"),
        }
    }

    /// The view's fragment stage in forward_views.wgsl (pixel shading), or `shading`'s.
    fn stages(self, shading: Shading) -> Stages {
        let fragment = match self {
            View::Shaded => return shading.stages(false),
            View::Shadows => "fs_shadows_view",
            View::Cascades => "fs_cascades_view",
        };
        Stages {
            fragment,
            ..Shading::Pixel.stages(false)
        }
    }
}

/// How often the forward pass runs its fragment shader.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Shading {
    /// Once per pixel and triangle; the result is written to every covered sample.
    #[default]
    Pixel,
    /// Once per covered sample.
    Sample,
}

use TextureFormat as F;
/// Forward shading needs no stencil, so depth-only formats do too.
pub(crate) const DEPTH: &[TextureFormat] = &[
    F::Depth24Plus,
    F::Depth32Float,
    F::Depth24PlusStencil8,
    F::Depth32FloatStencil8,
];

impl Shading {
    /// forward.wgsl's entry points, or transparent.wgsl's for the `blended` meshes; alpha
    /// masks through the constant `MASKED`.
    pub(crate) fn stages(self, blended: bool) -> Stages {
        let (vertex, fragment) = match (self, blended) {
            (Shading::Pixel, false) => ("vs_pixel", "fs_pixel"),
            (Shading::Sample, false) => ("vs_sample", "fs_sample"),
            (Shading::Pixel, true) => ("vs_pixel", "fs_blend_pixel"),
            (Shading::Sample, true) => ("vs_sample", "fs_blend_sample"),
        };
        Stages {
            vertex,
            fragment,
            masked: Masked::Constant,
        }
    }
}

impl Plugin for Forward {
    const NAME: &'static str = "forward";
    type Params = ForwardParams;

    fn kind(&self, _: &ForwardParams) -> PassKind {
        PassKind::Render
    }

    fn setup(
        &self,
        params: ForwardParams,
        pass: &mut PassBuilder<'_>,
        slots: &mut Slots<'_>,
    ) -> Result<(), PluginError> {
        let depth_rule = DepthRule::new(params.reversed_z);
        let want = Want::new("the forward pass's depth", DEPTH);
        let (depth, desc) = textures::output(slots, pass, "depth", want, |pass, h, _| {
            depth_rule.start(pass, h)
        })?;
        let want = match params.view {
            View::Shaded => Want::new("the HDR target", textures::HDR),
            View::Shadows | View::Cascades => Want::new("the debug view", textures::DISPLAY),
        };
        let want = want.samples(desc.samples);
        // Filled with the background where no mesh draws rather than cleared first
        // (common/background.rs), unless the pass draws over the target it reads. A view
        // shows black there.
        let background = match params.view {
            View::Shaded => params.background,
            View::Shadows | View::Cascades => opaque_black(),
        };
        let mut targets = FilledTargets::new(slots, &["hdr"]);
        targets.push(slots, pass, "hdr", want, ("vec4<f32>", background))?;
        let shadows = shadows::input(slots, pass)?;
        // A view of the shadow maps needs them.
        if let Some(view) = params.view.of_shadow_maps() {
            if shadows.is_none() {
                return Err(PluginError::MissingSlot {
                    slot: "shadows".to_owned(),
                    side: "inputs",
                });
            }
            if slots.optional("shadows") {
                return Err(PluginError::Slot {
                    slot: "shadows".to_owned(),
                    resource: slots.resource("shadows").unwrap_or_default().to_owned(),
                    why: format!(
                        "is read optionally, but view {view} draws the shadow maps: the \
                         read must be required (drop it from `optional`)"
                    ),
                });
            }
        }
        let source = match params.view {
            View::Shaded => shaders::FORWARD,
            View::Shadows | View::Cascades => shaders::FORWARD_VIEWS,
        };
        let filter = self.0.overrides.shadows.filter;
        let (fill_background, wgsl) = (targets.fill(), targets.wgsl());
        let handles = targets.into_handles();
        let draw = shadows::variants(shadows::optional(slots), shadows, |shadows| {
            // Group 1 is the material's: the atlas is bound in group 2.
            let generated = wgsl.clone() + &shadows::wgsl(shadows, 2, filter);
            let source = source.compose_with(desc.samples, &generated)?;
            Ok(SceneDraw {
                fill_background,
                shadows: shadows.copied(),
                ..SceneDraw::new(
                    "forward",
                    GatedShader::Forward,
                    source.source().to_owned(),
                    depth_rule,
                    handles.clone(),
                    depth,
                    params.view.stages(params.shading),
                )
            })
        })?;
        self.0.record(pass, draw);
        Ok(())
    }
}
