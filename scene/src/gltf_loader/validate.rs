//! The `gltf` crate's validation, made safe to run on any input.

use gltf::json::validation::{Checked, Error};
use gltf::json::Path;
use gltf::Semantic;

/// Validates the document (index ranges, enum values, required fields). Call after
/// `extensions::check`.
///
/// Two adjustments: the crate rejects required extensions it does not know itself (like
/// KHR_mesh_quantization) even when this loader implements them, so the list, already vetted,
/// is emptied first; and the crate's primitive check indexes `accessors` with the POSITION
/// index before range-checking it, so out-of-range POSITION indices are reported here instead
/// of panicking there.
pub(super) fn validate(document: gltf::Document) -> Result<gltf::Document, gltf::Error> {
    let mut json = document.into_json();
    json.extensions_required.clear();
    let accessor_count = json.accessors.len();
    let bad_positions: Vec<(Path, Error)> = json
        .meshes
        .iter()
        .enumerate()
        .flat_map(|(m, mesh)| {
            mesh.primitives
                .iter()
                .enumerate()
                .map(move |(p, primitive)| (m, p, primitive))
        })
        .filter(|(_, _, primitive)| {
            primitive
                .attributes
                .get(&Checked::Valid(Semantic::Positions))
                .is_some_and(|index| index.value() >= accessor_count)
        })
        .map(|(m, p, _)| {
            let path = Path::new()
                .field("meshes")
                .index(m)
                .field("primitives")
                .index(p)
                .field("attributes")
                .key("POSITION");
            (path, Error::IndexOutOfBounds)
        })
        .collect();
    if !bad_positions.is_empty() {
        return Err(gltf::Error::Validation(bad_positions));
    }
    gltf::Document::from_json(json)
}
