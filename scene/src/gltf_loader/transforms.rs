//! Node transforms in f64, read from the JSON text.
//!
//! The `gltf` crate parses `matrix`, `translation`, `rotation` and `scale` as f32, which
//! quantises a node 1e6 units from the origin to 1/16 unit before any f64 math: silhouettes
//! move by a pixel. So the same fields are read again here, as f64, from the JSON (the file
//! itself, or a GLB's JSON chunk).

use std::path::Path;

use glam::{DMat4, DQuat, DVec3, DVec4};

use crate::node_tree::{LocalTransform, Trs};

use crate::error::label;
use crate::SceneError;

/// The transform fields of one node, as written.
#[derive(Default, serde::Deserialize)]
struct NodeJson {
    matrix: Option<[f64; 16]>,
    translation: Option<[f64; 3]>,
    rotation: Option<[f64; 4]>,
    scale: Option<[f64; 3]>,
}

#[derive(serde::Deserialize)]
struct DocumentJson {
    #[serde(default)]
    nodes: Vec<NodeJson>,
}

/// Each node's transform relative to its parent, by node index, from the glTF file's JSON
/// text (the file, or a GLB's JSON chunk). `document` is the same JSON as parsed by `gltf`,
/// for names in errors. Fails, naming the node, on a value that is not a finite f64 (JSON has
/// no infinity, but `1e400` overflows).
pub(super) fn read(
    file: &Path,
    json: &[u8],
    document: &gltf::Document,
) -> Result<Vec<LocalTransform>, SceneError> {
    let parsed: DocumentJson = serde_json::from_slice(json).map_err(|e| {
        // `gltf` read every field already, so only a number out of f64's range gets here.
        SceneError::InvalidNode {
            file: file.to_owned(),
            node: "a node".to_owned(),
            reason: format!("a transform cannot be read as f64: {e}"),
        }
    })?;
    document
        .nodes()
        .map(|node| {
            let fields = parsed.nodes.get(node.index());
            let transform = fields.map_or(LocalTransform::Trs(Trs::IDENTITY), local_transform);
            if !transform.matrix().is_finite() {
                return Err(SceneError::InvalidNode {
                    file: file.to_owned(),
                    node: label("node", node.index(), node.name()),
                    reason: "its transform is not finite".to_owned(),
                });
            }
            Ok(transform)
        })
        .collect()
}

/// The node's transform relative to its parent: `matrix` when present, else translation,
/// rotation and scale (each defaulting as glTF says).
fn local_transform(node: &NodeJson) -> LocalTransform {
    if let Some(matrix) = node.matrix {
        return LocalTransform::Matrix(DMat4::from_cols_array(&matrix));
    }
    // Exporters write slightly unnormalized quaternions; an all-zero one (invalid) is taken
    // as no rotation rather than filling every position with NaN.
    let rotation = node
        .rotation
        .map(DVec4::from_array)
        .and_then(DVec4::try_normalize)
        .map_or(DQuat::IDENTITY, DQuat::from_vec4);
    LocalTransform::Trs(Trs {
        translation: node.translation.map_or(DVec3::ZERO, DVec3::from_array),
        rotation,
        scale: node.scale.map_or(DVec3::ONE, DVec3::from_array),
    })
}
