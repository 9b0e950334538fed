//! `debug_view`: shows one aspect of the G-buffer or the edge stencil, read at sample 0,
//! in a displayable texture. Graph files export them as `debug.NAME`, which the render
//! command's `--view NAME` picks.
//!
//! ```ron
//! (name: "debug edges", plugin: "debug_view",
//!  params: (view: edges),   // or albedo | normals | depth | lights
//!  inputs: { "depth": "depth_edges", "view_depth": "view_depth" },
//!  outputs: { "color": "debug.edges" })   // rgba8unorm-srgb (or rgba8unorm), 1 sample
//! ```
//!
//! Views and the inputs each reads:
//! - `edges` (`depth`, the depth-stencil after the edge pass, and `view_depth`): red
//!   where lighting runs per sample (stencil 0x80), blue where once per pixel, black
//!   without geometry, as seed 003 shows it;
//! - `albedo` (`albedo`);
//! - `normals` (`normal`, `view_depth`): world-space normal mapped to [0, 1];
//! - `depth` (`view_depth`): `1 / (1 + depth / depth_scale)`, black without geometry;
//! - `lights` (`material`, `view_depth`): how many lights reach each lit surface point
//!   (directional lights count; point and spot lights within their range and cone), as a
//!   heat ramp from blue (1) through cyan, green and yellow to red (`heat_max` or more).
//!   This is what light passes with exact volumes would shade there; the rasterized
//!   volumes also touch pixels outside them, which the shader then gives nothing.

use serde::Deserialize;

use rgraph_core::file::{Plugin, PluginError, Slots};
use rgraph_core::{Aspect, PassBuilder, PassKind};

use crate::common::fullscreen::Fullscreen;
use crate::common::plugin::Shared;
use crate::common::textures::{self, Input, Texels, Want};
use crate::shaders;

pub struct DebugView(pub(crate) Shared);

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DebugViewParams {
    pub view: View,
    #[serde(default = "depth_scale")]
    pub depth_scale: f32,
    #[serde(default = "heat_max")]
    pub heat_max: u32,
}

fn depth_scale() -> f32 {
    10.0
}
fn heat_max() -> u32 {
    16
}

#[derive(Copy, Clone, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum View {
    Edges,
    Albedo,
    Normals,
    Depth,
    Lights,
}

/// A G-buffer texture a view may read: slot, description, formats, group-1 binding.
type Read = (
    &'static str,
    &'static str,
    &'static [rgraph_core::types::TextureFormat],
    u32,
);

const ALBEDO: Read = ("albedo", "the G-buffer's albedo", textures::ALBEDO, 0);
const NORMAL: Read = ("normal", "the G-buffer's normals", textures::NORMAL, 1);
const MATERIAL: Read = ("material", "the G-buffer's material", textures::MATERIAL, 2);
const VIEW_DEPTH: Read = (
    "view_depth",
    "the G-buffer's view depth",
    textures::VIEW_DEPTH,
    3,
);

impl Plugin for DebugView {
    const NAME: &'static str = "debug_view";
    type Params = DebugViewParams;

    fn kind(&self, _: &DebugViewParams) -> PassKind {
        PassKind::Render
    }

    fn setup(
        &self,
        params: DebugViewParams,
        pass: &mut PassBuilder<'_>,
        slots: &mut Slots<'_>,
    ) -> Result<(), PluginError> {
        if !(params.depth_scale.is_finite() && params.depth_scale > 0.0) {
            return Err(PluginError::Invalid(format!(
                "depth_scale must be finite and positive, got {}",
                params.depth_scale
            )));
        }
        let (entry, reads): (&str, &[Read]) = match params.view {
            View::Edges => ("fs_edges", &[VIEW_DEPTH]),
            View::Albedo => ("fs_albedo", &[ALBEDO]),
            View::Normals => ("fs_normals", &[NORMAL, VIEW_DEPTH]),
            View::Depth => ("fs_depth", &[VIEW_DEPTH]),
            View::Lights => ("fs_lights", &[MATERIAL, VIEW_DEPTH]),
        };
        let mut inputs = Vec::new();
        // The first input sets the sample count the others must have.
        let mut samples = None;
        if params.view == View::Edges {
            let want = Want::new(
                "the depth-stencil with the edge stencil",
                textures::DEPTH_STENCIL,
            );
            let (handle, desc) = textures::input(slots, pass, "depth", want)?;
            pass.sampled_aspect(handle, Aspect::StencilOnly);
            inputs.push(Input {
                binding: 4,
                texture: handle,
                aspect: Aspect::StencilOnly,
                texels: Texels::Uint,
            });
            samples = Some(desc.samples);
        }
        for &(slot, what, formats, binding) in reads {
            let want = Want {
                samples,
                ..Want::new(what, formats)
            };
            let (input, desc) = textures::sampled(slots, pass, slot, want, binding)?;
            samples = Some(desc.samples);
            inputs.push(input);
        }
        let want = Want::new("a debug view", textures::DISPLAY).samples(1);
        let (target, _) = textures::covered_output(slots, pass, "color", want)?;
        let source = shaders::DEBUG
            .compose(samples.unwrap_or(1))?
            .source()
            .to_owned();
        let draw = Fullscreen {
            constants: vec![
                ("DEPTH_SCALE", f64::from(params.depth_scale)),
                ("HEAT_MAX", f64::from(params.heat_max)),
            ],
            reads_scene: params.view == View::Lights,
            ..Fullscreen::new("debug_view", source, entry, inputs, Some(target))
        };
        self.0.record(pass, draw);
        Ok(())
    }
}
