//! World transforms checked against what a scene can hold.

use std::path::Path;

use glam::DMat4;

use crate::error::label;
use crate::{SceneError, MAX_COORDINATE};

/// Fails, naming `node`, on a world transform with an entry beyond ±[`MAX_COORDINATE`] (a
/// translation or scale of 1e39, or many large scales multiplied) or one that is not
/// finite, rather than a frame that is empty because f32 overflowed on the way to the GPU:
/// the transform of `node` itself (`whose` is "its") or of one of its instances
/// ("instance 3's").
pub(super) fn check(
    file: &Path,
    node: &gltf::Node,
    world: &DMat4,
    whose: &str,
) -> Result<(), SceneError> {
    let largest = world
        .to_cols_array()
        .into_iter()
        .map(f64::abs)
        .fold(0.0, f64::max);
    // `f64::max` skips NaN, hence the finiteness test (inf * 0 composes to NaN).
    if !world.is_finite() || largest > MAX_COORDINATE {
        return Err(SceneError::InvalidNode {
            file: file.to_owned(),
            node: label("node", node.index(), node.name()),
            reason: format!(
                "{whose} world transform has an entry of {largest:e}, beyond ±{MAX_COORDINATE:e} \
                 (the largest coordinate a scene may have)"
            ),
        });
    }
    Ok(())
}
