//! The `blit` plugin; its contract is on [`Blit`].

use serde::Deserialize;

use super::binding::{BindingDecl, Filter};
use super::draw::{Blend, Draw};
use crate::builder::PassBuilder;
use crate::file::{Plugin, PluginError, Slots};
use crate::pass::PassKind;
use crate::shader::Shader;

/// `blit`: copies input slot `src` into output slot `dst` by sampling, so the two may
/// differ in size and format (an `rgba16float` image into an `rgba8unorm-srgb` target).
/// `src` must be a single-sampled float texture; resolve multisampled ones first.
///
/// ```ron
/// (name: "present", plugin: "blit", params: (filter: Nearest),   // default Linear
///  inputs: { "src": "hdr" }, outputs: { "dst": "target" })
/// ```
pub struct Blit;

/// `blit`'s parameters.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BlitParams {
    /// How `src` is sampled where the sizes differ; linear by default.
    #[serde(default)]
    pub filter: Filter,
}

impl Plugin for Blit {
    const NAME: &'static str = "blit";
    type Params = BlitParams;

    fn kind(&self, _: &BlitParams) -> PassKind {
        PassKind::Render
    }

    fn setup(
        &self,
        params: BlitParams,
        pass: &mut PassBuilder<'_>,
        slots: &mut Slots<'_>,
    ) -> Result<(), PluginError> {
        if !slots.is_output("dst") {
            return Err(PluginError::MissingSlot {
                slot: "dst".into(),
                side: "outputs",
            });
        }
        let bindings = [
            BindingDecl::Slot {
                group: 0,
                binding: 0,
                slot: "src".into(),
            },
            BindingDecl::Sampler {
                group: 0,
                binding: 1,
                filter: params.filter,
            },
        ];
        Draw {
            shader: Shader::parse("built-in blit.wgsl", include_str!("blit.wgsl"))?,
            entry: "fs_main",
            bindings: &bindings,
            blend: Blend::Replace,
            clear: [0.0; 4],
        }
        .setup(pass, slots)
    }
}
