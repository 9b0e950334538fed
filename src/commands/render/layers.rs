//! What a G-buffer leaves out: it stores the core metallic-roughness model only (no bytes
//! per sample are free for more, docs/design/lighting-real-content.md says what each
//! extension would cost), so a pipeline that shades opaque surfaces from one, or from a
//! light pre-pass's thin one, leaves out the layers of KHR_materials_ior, _specular,
//! _clearcoat and _sheen there. The visibility buffer and forward pipelines shade them,
//! and so does every pipeline's transparent pass (forward shading) for BLEND materials.

use std::collections::BTreeMap;
use std::path::Path;

use rgraph_scene::{AlphaMode, Scene};

/// One warning per extension whose layer opaque meshes of `scene` use, for a pipeline
/// (`pipeline`, for the message) that shades them from a G-buffer: the first material
/// using it by name, and how many others do.
pub(super) fn unshaded(scene: &Scene, pipeline: &Path) -> Vec<String> {
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
    users
        .into_iter()
        .map(|(extension, materials)| {
            let others = match materials.len() - 1 {
                0 => String::new(),
                1 => " and 1 other material".to_owned(),
                n => format!(" and {n} other materials"),
            };
            format!(
                "warning: {}{others} uses {extension}, but {} shades opaque surfaces from a \
                 G-buffer, which does not store it: its effect is left out there \
                 (pipelines/visibility_msaa_4x.ron and forward_msaa_4x.ron shade it)",
                materials[0],
                pipeline.display()
            )
        })
        .collect()
}
