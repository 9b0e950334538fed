//! The material layers' targets of a G-buffer (crate::layers), as the passes that write
//! and read them take them: their formats and bindings, which of them a frame's plan
//! keeps ([`LayerSet`]), and the WGSL that reads a set of them (gbuffer_layers.wgsl
//! encodes and decodes each).
//!
//! | slot | format | holds | bytes per sample |
//! | --- | --- | --- | --: |
//! | `specular` | rgba8unorm | the dielectric F0 as its square root, the specular weight | 4 |
//! | `clearcoat` | rg8unorm | strength, roughness | 2 |
//! | | rgba16float | strength, roughness and the coat's octahedral normal, where it bends apart from its base (feature `clearcoat_normal`) | 8 |
//! | `sheen` | rgba8unorm | the colour as its square root, roughness | 4 |
//!
//! A file lists the slots `optional` and declares each target under its layer's feature,
//! so which layers a frame has is the plan's to say and is known only when recording: a
//! pass set up with layer slots records through `PerKept` (common/optional_targets.rs),
//! which makes the pass for the layers the plan keeps (composing its shader for them) the
//! first time a frame needs them.

use rgraph_core::file::{PluginError, Slots};
use rgraph_core::types::TextureFormat;
use rgraph_core::{PassBuilder, TextureHandle};

use super::background::FilledTargets;
use super::optional_targets::OptionalTargets;
use super::textures::{self, Input, Want};
use crate::layers::Layer;
use crate::shaders;

impl Layer {
    /// What the target is, in messages.
    fn what(self) -> &'static str {
        match self {
            Layer::Specular => "the G-buffer's specular layer",
            Layer::Clearcoat => "the G-buffer's clear coat",
            Layer::Sheen => "the G-buffer's sheen",
        }
    }

    /// The formats its target may have (the module documentation's table).
    pub(crate) fn formats(self) -> &'static [TextureFormat] {
        use TextureFormat as F;
        match self {
            Layer::Specular | Layer::Sheen => &[F::Rgba8Unorm],
            Layer::Clearcoat => &[F::Rg8Unorm, COAT_WITH_NORMAL],
        }
    }

    /// Where the passes that light a G-buffer bind it (group 1): after gbuffer_read.wgsl's
    /// bindings (0 to 5), the emission (6), light_tiled's output (7) and the ambient
    /// occlusion or a compute rasteriser's samples (8).
    fn binding(self) -> u32 {
        match self {
            Layer::Specular => 9,
            Layer::Clearcoat => 10,
            Layer::Sheen => 11,
        }
    }
}

/// The clear coat's target where it holds the coat's own normal.
const COAT_WITH_NORMAL: TextureFormat = TextureFormat::Rgba16Float;

/// The layer targets a pass's file lists, each as the pass declared it.
pub(crate) type LayerTargets = Vec<(Layer, TextureHandle)>;

/// Which layers a G-buffer holds in one frame.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Hash)]
pub(crate) struct LayerSet {
    held: [bool; 3],
    /// The clear coat's target holds its own normal (rgba16float).
    pub coat_normal: bool,
}

impl LayerSet {
    /// Every layer of `targets`, the coat with its normal if `targets` has one: the most
    /// a pass set up with them meets, which its setup checks.
    pub fn all(targets: &LayerTargets) -> LayerSet {
        let mut set = LayerSet::default();
        for &(layer, _) in targets {
            set.held[layer as usize] = true;
        }
        set.coat_normal = set.has(Layer::Clearcoat);
        set
    }

    /// The set of `targets` that `has` keeps, the coat's normal as `coat_format` says.
    #[cfg_attr(not(feature = "gpu"), allow(dead_code))]
    pub fn kept(
        targets: &LayerTargets,
        has: impl Fn(TextureHandle) -> bool,
        coat_format: impl Fn(TextureHandle) -> TextureFormat,
    ) -> LayerSet {
        let mut set = LayerSet::default();
        for &(layer, handle) in targets {
            if has(handle) {
                set.held[layer as usize] = true;
                set.coat_normal |=
                    layer == Layer::Clearcoat && coat_format(handle) == COAT_WITH_NORMAL;
            }
        }
        set
    }

    pub fn has(self, layer: Layer) -> bool {
        self.held[layer as usize]
    }

    /// Whether `handle`, one of `targets` or another texture, is held: every texture
    /// that is not a layer's is.
    pub fn keeps(self, targets: &LayerTargets, handle: TextureHandle) -> bool {
        targets
            .iter()
            .find(|&&(_, h)| h == handle)
            .is_none_or(|&(layer, _)| self.has(layer))
    }

    /// `inputs` without the layer textures this set does not hold.
    pub fn inputs(self, targets: &LayerTargets, inputs: &[Input]) -> Vec<Input> {
        let kept = inputs.iter().filter(|i| self.keeps(targets, i.texture));
        kept.copied().collect()
    }
}

/// Declares the layer slots the file gives a pass that lights a G-buffer of `samples`
/// sampled, and adds them to `inputs` at their bindings.
pub(crate) fn inputs(
    slots: &mut Slots<'_>,
    pass: &mut PassBuilder<'_>,
    samples: u32,
    inputs: &mut Vec<Input>,
) -> Result<LayerTargets, PluginError> {
    let mut targets = Vec::new();
    for layer in Layer::ALL {
        if slots.kind(layer.slot()).is_none() {
            continue;
        }
        let want = Want::new(layer.what(), layer.formats()).samples(samples);
        let (input, _) = textures::sampled(slots, pass, layer.slot(), want, layer.binding())?;
        inputs.push(input);
        targets.push((layer, input.texture));
    }
    Ok(targets)
}

/// The WGSL type a pass writing a G-buffer writes each layer's target as
/// (gbuffer_layers.wgsl's encodings).
pub(crate) const TARGET_WGSL: &str = "vec4<f32>";

/// Declares the layer slots the file gives a pass that writes a G-buffer of `samples` as
/// the next attachments of `targets`, after the pass's others, holding zeros where no
/// mesh draws.
pub(crate) fn push_targets(
    slots: &mut Slots<'_>,
    pass: &mut PassBuilder<'_>,
    samples: u32,
    targets: &mut FilledTargets,
) -> Result<LayerTargets, PluginError> {
    let mut layers = Vec::new();
    for layer in Layer::ALL {
        if !slots.is_output(layer.slot()) {
            continue;
        }
        let want = Want::new(layer.what(), layer.formats()).samples(samples);
        let target = targets.push(slots, pass, layer.slot(), want, (TARGET_WGSL, [0.0; 4]))?;
        layers.push((layer, target));
    }
    Ok(layers)
}

/// The WGSL after gbuffer_read.wgsl that reads the layers of `set` (group 1, at their
/// bindings) as its `load_layers`, which decodes each through gbuffer_layers.wgsl:
/// gbuffer_core_layers.wgsl's where the set is empty.
pub(crate) fn read_wgsl(set: LayerSet) -> String {
    if Layer::ALL.into_iter().all(|l| !set.has(l)) {
        return shaders::GBUFFER_CORE_LAYERS.to_owned();
    }
    let mut bindings = String::new();
    let mut decoded = String::new();
    for layer in Layer::ALL.into_iter().filter(|&l| set.has(l)) {
        let slot = layer.slot();
        bindings += &format!(
            "@group(1) @binding({}) var {slot}_tex: GTexF;\n",
            layer.binding()
        );
        let texel = format!("textureLoad({slot}_tex, pixel, s)");
        decoded += &match layer {
            Layer::Clearcoat => format!(
                "    layers = decode_clearcoat(layers, {texel}, normal, {});\n",
                set.coat_normal
            ),
            _ => format!("    layers = decode_{slot}(layers, {texel});\n"),
        };
    }
    format!(
        "// Generated: the material layers the G-buffer holds (common/gbuffer_layers.rs).\n\
         {bindings}\n\
         fn load_layers(pixel: vec2<i32>, s: u32, normal: vec3<f32>) -> Layers {{\n\
         \x20   var layers = plain_layers();\n{decoded}    return layers;\n}}\n"
    )
}

/// The layer targets a pass's file lists, kept as a frame's plan says: every one (the
/// coat with its normal) at most.
impl OptionalTargets for LayerTargets {
    type Set = LayerSet;

    fn is_empty(&self) -> bool {
        Vec::is_empty(self)
    }

    fn all(&self) -> LayerSet {
        LayerSet::all(self)
    }

    fn kept(
        &self,
        has: &dyn Fn(TextureHandle) -> bool,
        format: &dyn Fn(TextureHandle) -> TextureFormat,
    ) -> LayerSet {
        LayerSet::kept(self, has, format)
    }

    fn keeps(&self, set: LayerSet, handle: TextureHandle) -> bool {
        set.keeps(self, handle)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_reader_decodes_the_layers_held_and_the_core_model_s_without_any() {
        let set = LayerSet {
            held: [true, true, false],
            coat_normal: false,
        };
        let wgsl = read_wgsl(set);
        assert!(
            wgsl.contains("@group(1) @binding(9) var specular_tex: GTexF;"),
            "{wgsl}"
        );
        assert!(
            wgsl.contains("@group(1) @binding(10) var clearcoat_tex: GTexF;"),
            "{wgsl}"
        );
        assert!(!wgsl.contains("sheen_tex"), "{wgsl}");
        assert!(
            wgsl.contains(
                "decode_clearcoat(layers, textureLoad(clearcoat_tex, pixel, s), normal, false)"
            ),
            "{wgsl}"
        );
        assert_eq!(read_wgsl(LayerSet::default()), shaders::GBUFFER_CORE_LAYERS);
    }
}
