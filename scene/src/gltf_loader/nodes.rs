//! The node hierarchy flattened into world transforms.

use std::path::Path;

use glam::DMat4;

use crate::error::label;
use crate::{SceneError, MAX_COORDINATE};

/// A node reached from a scene root, with its object-to-world transform.
pub(super) struct Placed<'a> {
    pub node: gltf::Node<'a>,
    pub world: DMat4,
}

/// Every node of `scene`, depth first, parents before children, siblings in file order (so
/// "the first camera in the scene" means the first in this order). `local` is each node's
/// transform relative to its parent, by index (see [`super::transforms`]); they are composed
/// in f64 so large translations survive. Iterative, so deep hierarchies cannot overflow the
/// stack.
///
/// A world transform with an entry beyond ±[`MAX_COORDINATE`] (a translation or scale of
/// 1e39, or many large scales multiplied) is an error naming the node, rather than a frame
/// that is empty because f32 overflowed on the way to the GPU.
///
/// glTF requires the hierarchy to be a forest; a node reached twice (a cycle or a shared child)
/// is an error rather than an endless or duplicated traversal.
pub(super) fn flatten<'a>(
    file: &Path,
    document: &'a gltf::Document,
    scene: &gltf::Scene<'a>,
    local: &[DMat4],
) -> Result<Vec<Placed<'a>>, SceneError> {
    let mut seen = vec![false; document.nodes().len()];
    let mut stack: Vec<(gltf::Node<'a>, DMat4)> =
        scene.nodes().map(|n| (n, DMat4::IDENTITY)).collect();
    stack.reverse();
    let mut placed = Vec::new();
    while let Some((node, parent)) = stack.pop() {
        if std::mem::replace(&mut seen[node.index()], true) {
            return Err(SceneError::NodeHierarchy {
                file: file.to_owned(),
                node: label("node", node.index(), node.name()),
            });
        }
        let world = parent * local[node.index()];
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
                    "its world transform has an entry of {largest:e}, beyond ±{MAX_COORDINATE:e} \
                     (the largest coordinate a scene may have)"
                ),
            });
        }
        let children: Vec<_> = node.children().collect();
        stack.extend(children.into_iter().rev().map(|child| (child, world)));
        placed.push(Placed { node, world });
    }
    Ok(placed)
}
