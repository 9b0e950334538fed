//! The material layers a G-buffer can store (KHR_materials_ior and _specular, _clearcoat,
//! _sheen), and which of them a plan's G-buffer lighting leaves out, for tools that warn
//! about it (`rgraph render`).
//!
//! A G-buffer pass writes a layer into a target of its own, in the slot the layer names,
//! and the passes that light the G-buffer read it back through the same slot (the
//! formats and the encoding: passes/src/wgsl/gbuffer_layers.wgsl). Files declare each
//! target under the layer's scene feature (`specular`, `clearcoat`, `sheen`) and list the
//! slots `optional`, so a plan keeps a layer's bytes only for a scene whose materials use
//! it, and a core scene's G-buffer is the one it was without layers.

use rgraph_core::file::LoadedGraph;
use rgraph_core::Plan;

/// A material layer a G-buffer stores in a target of its own.
#[derive(Copy, Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Layer {
    /// KHR_materials_ior and _specular: the dielectric F0 and the specular weight.
    Specular,
    /// KHR_materials_clearcoat: the coat's strength, roughness and (where it bends apart
    /// from its base) normal.
    Clearcoat,
    /// KHR_materials_sheen: the sheen's colour and roughness.
    Sheen,
}

impl Layer {
    /// Every layer, in attachment and binding order.
    pub const ALL: [Layer; 3] = [Layer::Specular, Layer::Clearcoat, Layer::Sheen];

    /// The slot that holds it, in the passes that write a G-buffer and those that read
    /// one (and the name the shipped pipelines give its target).
    pub fn slot(self) -> &'static str {
        match self {
            Layer::Specular => "specular",
            Layer::Clearcoat => "clearcoat",
            Layer::Sheen => "sheen",
        }
    }

    /// The glTF extensions whose effect it holds, as `Material::layer_extensions` names
    /// them.
    pub fn extensions(self) -> &'static [&'static str] {
        match self {
            Layer::Specular => &["KHR_materials_ior", "KHR_materials_specular"],
            Layer::Clearcoat => &["KHR_materials_clearcoat"],
            Layer::Sheen => &["KHR_materials_sheen"],
        }
    }

    /// The layer holding `extension`'s effect, if one does.
    pub fn of_extension(extension: &str) -> Option<Layer> {
        Layer::ALL
            .into_iter()
            .find(|l| l.extensions().contains(&extension))
    }
}

/// A pass of a plan that lights opaque surfaces from a G-buffer without one of the
/// layers that lighting needs from it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Unshaded {
    /// The layer left out.
    pub layer: Layer,
    /// The pass, by name.
    pub pass: String,
}

/// The layers each pass of `plan` (compiled from `loaded`) that lights a G-buffer leaves
/// out: a `light_edge`, `light_nonedge` or `light_tiled` pass shading from G-buffer
/// channels (not a visibility buffer's, whose shading reads every layer from the material
/// table; not a debug view) whose file gives it no slot for the layer, or whose plan
/// drops its read (the scene has no such layer, or the device cannot hold the target). A
/// light pre-pass's light passes (no `albedo`) need only the coat and the sheen: the
/// material pass applies the specular layer itself. Empty for a plan that lights no
/// G-buffer.
pub fn unshaded(plan: &Plan, loaded: &LoadedGraph) -> Vec<Unshaded> {
    let mut left_out = Vec::new();
    for pass in &plan.passes {
        let name = pass.name.as_str();
        let lights = matches!(
            loaded.plugin(name),
            Some("light_edge" | "light_nonedge" | "light_tiled")
        );
        let slot = |slot| loaded.slot(name, slot);
        let shades = slot("hdr").is_some() || slot("resolved").is_some();
        if !lights || !shades || slot("normal").is_none() {
            continue;
        }
        let prepass = slot("albedo").is_none();
        for layer in Layer::ALL {
            if prepass && layer == Layer::Specular {
                continue;
            }
            let read = slot(layer.slot()).is_some_and(|h| pass.reads_resource(h.id()));
            if !read {
                left_out.push(Unshaded {
                    layer,
                    pass: name.to_owned(),
                });
            }
        }
    }
    left_out
}
