//! What a G-buffer leaves out: a pipeline's G-buffer stores the material layers of
//! KHR_materials_ior, _specular, _clearcoat and _sheen only where its plan keeps their
//! targets (the scene uses them, and the device's render passes hold more than WebGPU's
//! 32 bytes per sample of colour targets: docs/design/lighting-real-content.md, "Material
//! layers"), and a pipeline whose lighting reads no such target (the G-buffer resolve's,
//! say) leaves the layer out of the opaque surfaces it shades. The visibility buffer and
//! forward pipelines shade every layer, and so does every pipeline's transparent pass
//! (forward shading) for BLEND materials.

use std::collections::BTreeMap;
use std::path::Path;

use rgraph_core::file::LoadedGraph;
use rgraph_core::Plan;
use rgraph_passes::layers::{self, Layer};
use rgraph_scene::{AlphaMode, Scene};

use super::color_bytes;

/// One warning per extension whose layer opaque meshes of `scene` use and some pass of
/// `plan` (compiled from `loaded`, the file `pipeline`) lights from a G-buffer without:
/// the first material using it by name, how many others do, the first such pass, and
/// why where the device is the reason.
pub(super) fn unshaded(
    scene: &Scene,
    plan: &Plan,
    loaded: &LoadedGraph,
    pipeline: &Path,
) -> Vec<String> {
    let left_out = layers::unshaded(plan, loaded);
    let pass_without = |layer: Layer| left_out.iter().find(|u| u.layer == layer);
    let mut users: BTreeMap<&str, Vec<&str>> = BTreeMap::new();
    let mut seen = vec![false; scene.materials.len()];
    for mesh in &scene.meshes {
        let Some(material) = scene.materials.get(mesh.material) else {
            continue;
        };
        if material.alpha_mode == AlphaMode::Blend
            || std::mem::replace(&mut seen[mesh.material], true)
        {
            continue;
        }
        for extension in material.layer_extensions() {
            users.entry(extension).or_default().push(&material.name);
        }
    }
    // The shipped files store the layers only where the device allows it.
    let device = color_bytes::lacking(plan, loaded, "the layers");
    users
        .into_iter()
        .filter_map(|(extension, materials)| {
            let unshaded = pass_without(Layer::of_extension(extension)?)?;
            let others = match materials.len() - 1 {
                0 => String::new(),
                1 => " and 1 other material".to_owned(),
                n => format!(" and {n} other materials"),
            };
            Some(format!(
                "warning: {}{others} uses {extension}, but pass \"{}\" of {} shades opaque \
                 surfaces from a G-buffer without it{device}: its effect is left out there \
                 (pipelines/visibility_msaa_4x.ron and forward_msaa_4x.ron shade it)",
                materials[0],
                unshaded.pass,
                pipeline.display()
            ))
        })
        .collect()
}
