//! glTF skins to [`Skin`]s: joints as nodes of the loaded scene's tree, inverse bind
//! matrices read and checked.
//!
//! A skin has 1 to [`MAX_JOINTS`] joints, each a node the loaded scene places (a joint
//! elsewhere could not be posed), and inverseBindMatrices, when given, is a MAT4 FLOAT
//! accessor with an element per joint or more (glTF allows extra ones), each finite.

use std::path::Path;

use glam::DMat4;
use gltf::accessor::{DataType, Dimensions};

use super::accessor::{self, component_name, type_name};
use crate::error::label;
use crate::node_tree::NodeId;
use crate::{SceneError, Skin, MAX_JOINTS};

/// Every skin of the file, in its order. `ids` maps a glTF node index to its node in the
/// loaded scene's tree.
pub(super) fn read(
    file: &Path,
    document: &gltf::Document,
    buffers: &[Vec<u8>],
    ids: &[Option<NodeId>],
) -> Result<Vec<Skin>, SceneError> {
    document
        .skins()
        .map(|skin| {
            let name = label("skin", skin.index(), skin.name());
            let error = |reason| SceneError::InvalidSkin {
                file: file.to_owned(),
                skin: name.clone(),
                reason,
            };
            let count = skin.joints().len();
            if count == 0 || count > MAX_JOINTS {
                return Err(error(format!(
                    "has {count} joints; a skin has 1 to {MAX_JOINTS}"
                )));
            }
            let joints = (skin.joints())
                .map(|joint| {
                    ids[joint.index()].ok_or_else(|| {
                        error(format!(
                            "joint {} is not in the loaded scene, so nothing could pose it",
                            label("node", joint.index(), joint.name())
                        ))
                    })
                })
                .collect::<Result<Vec<_>, _>>()?;
            let inverse_binds = match skin.inverse_bind_matrices() {
                None => vec![DMat4::IDENTITY; count],
                Some(matrices) => inverse_binds(buffers, &matrices, count).map_err(|reason| {
                    error(format!(
                        "inverseBindMatrices accessor {}: {reason}",
                        matrices.index()
                    ))
                })?,
            };
            Ok(Skin {
                name,
                joints,
                inverse_binds,
            })
        })
        .collect()
}

/// The first `joints` matrices of a MAT4 FLOAT accessor, each finite.
fn inverse_binds(
    buffers: &[Vec<u8>],
    matrices: &gltf::Accessor,
    joints: usize,
) -> Result<Vec<DMat4>, String> {
    let (dimensions, data_type) = (matrices.dimensions(), matrices.data_type());
    if dimensions != Dimensions::Mat4 || data_type != DataType::F32 || matrices.normalized() {
        return Err(format!(
            "is {} of {}, but inverse bind matrices are MAT4 of FLOAT",
            type_name(dimensions),
            component_name(data_type, matrices.normalized())
        ));
    }
    if matrices.count() < joints {
        return Err(format!(
            "has {} elements, fewer than the skin's {joints} joints",
            matrices.count()
        ));
    }
    let values = accessor::read_vectors::<16>(buffers, matrices)?;
    match values.iter().position(|m| m.iter().any(|c| !c.is_finite())) {
        Some(i) if i < joints => Err(format!("matrix {i} is not finite")),
        _ => Ok((values.iter().take(joints))
            .map(|m| DMat4::from_cols_array(&m.map(f64::from)))
            .collect()),
    }
}
