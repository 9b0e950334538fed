//! The glTF JSON parsed into the `gltf` crate's document, after accepting what the glTF
//! spec allows but gltf 1.4 rejects.
//!
//! A UTF-8 byte-order mark before the JSON, which the spec forbids and editors write, is
//! skipped.
//!
//! gltf 1.4 requires `scenes[i].nodes`, which the spec makes optional (an empty scene is
//! valid and the Khronos validator accepts it): such a scene gets an empty node list here
//! instead of failing the whole file with "missing field `nodes`".

use std::path::Path;

use serde_json::Value;

use crate::SceneError;

/// A parsed glTF file.
pub(super) struct Parsed {
    pub document: gltf::Document,
    /// The JSON text (the file itself, or a GLB's JSON chunk).
    pub json: Vec<u8>,
    /// A GLB's binary chunk.
    pub blob: Option<Vec<u8>>,
}

/// Parses `bytes` (`.gltf` JSON or `.glb`) without validating it (see `validate`). Errors
/// are [`SceneError::Gltf`] naming `file`, as the `gltf` crate's own parser would give.
pub(super) fn parse(file: &Path, bytes: &[u8]) -> Result<Parsed, SceneError> {
    let gltf_error = |source| SceneError::Gltf {
        file: file.to_owned(),
        source,
    };
    let (json, blob) = match bytes.starts_with(b"glTF") {
        true => {
            let glb = gltf::Glb::from_slice(bytes).map_err(gltf_error)?;
            (glb.json.into_owned(), glb.bin.map(|bin| bin.into_owned()))
        }
        false => (bytes.to_vec(), None),
    };
    // glTF forbids a byte-order mark, but Windows editors write one, invisibly; JSON
    // parsers stop at it ("expected value at line 1 column 1"), which says nothing useful.
    let json = match json.strip_prefix(b"\xEF\xBB\xBF") {
        Some(rest) => rest.to_vec(),
        None => json,
    };
    let deserialize = |e| gltf_error(gltf::Error::Deserialize(e));
    let mut value: Value = serde_json::from_slice(&json).map_err(deserialize)?;
    default_scene_nodes(&mut value);
    // Through text, not `from_value`: with the `extras` feature the document keeps raw JSON
    // values, which only a text deserializer can produce.
    let text = serde_json::to_vec(&value).map_err(deserialize)?;
    let root = gltf::json::deserialize::from_slice(&text).map_err(deserialize)?;
    Ok(Parsed {
        document: gltf::Document::from_json_without_validation(root),
        json,
        blob,
    })
}

/// Gives every scene object without `nodes` an empty list.
fn default_scene_nodes(root: &mut Value) {
    let scenes = root.get_mut("scenes").and_then(Value::as_array_mut);
    for scene in scenes
        .into_iter()
        .flatten()
        .filter_map(Value::as_object_mut)
    {
        scene
            .entry("nodes")
            .or_insert_with(|| Value::Array(Vec::new()));
    }
}
