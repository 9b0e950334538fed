//! Which glTF extensions are honored, and what happens to the others.

use std::path::Path;

use crate::SceneError;

/// Extensions whose effect on the rendered image this loader reproduces.
/// KHR_mesh_quantization needs no code of its own: the accessor reader decodes every component
/// type, normalized or not, and node transforms do the dequantization.
pub(super) const IMPLEMENTED: &[&str] = &[
    "EXT_mesh_gpu_instancing",
    "KHR_lights_punctual",
    "KHR_materials_clearcoat",
    "KHR_materials_emissive_strength",
    "KHR_materials_ior",
    "KHR_materials_pbrSpecularGlossiness",
    "KHR_materials_sheen",
    "KHR_materials_specular",
    "KHR_materials_unlit",
    "KHR_mesh_quantization",
    "KHR_texture_transform",
];

/// Fails on the first `extensionsRequired` entry that is not [`IMPLEMENTED`] (the file says it
/// cannot be rendered correctly without it); returns one warning per other `extensionsUsed`
/// entry that is not implemented (the file renders, minus that extension's effect).
pub(super) fn check(file: &Path, document: &gltf::Document) -> Result<Vec<String>, SceneError> {
    if let Some(missing) = document
        .extensions_required()
        .find(|e| !IMPLEMENTED.contains(e))
    {
        return Err(SceneError::UnsupportedRequiredExtension {
            file: file.to_owned(),
            extension: missing.to_owned(),
            implemented: IMPLEMENTED.join(", "),
        });
    }
    Ok(document
        .extensions_used()
        .filter(|e| !IMPLEMENTED.contains(e))
        .map(|e| format!("glTF extension {e} is not implemented; its effect is ignored"))
        .collect())
}
