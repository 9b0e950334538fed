//! The node hierarchy flattened into world transforms.

use std::path::Path;

use glam::{DMat4, DQuat, DVec3, DVec4};

use crate::scene::error::label;
use crate::scene::SceneError;

/// A node reached from a scene root, with its object-to-world transform.
pub(super) struct Placed<'a> {
    pub node: gltf::Node<'a>,
    pub world: DMat4,
}

/// Every node of `scene`, depth first, parents before children, siblings in file order (so
/// "the first camera in the scene" means the first in this order). Transforms are composed in
/// f64 so large translations survive. Iterative, so deep hierarchies cannot overflow the stack.
///
/// glTF requires the hierarchy to be a forest; a node reached twice (a cycle or a shared child)
/// is an error rather than an endless or duplicated traversal.
pub(super) fn flatten<'a>(
    file: &Path,
    document: &'a gltf::Document,
    scene: &gltf::Scene<'a>,
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
        let world = parent * local_transform(&node);
        let children: Vec<_> = node.children().collect();
        stack.extend(children.into_iter().rev().map(|child| (child, world)));
        placed.push(Placed { node, world });
    }
    Ok(placed)
}

/// The node's transform relative to its parent.
fn local_transform(node: &gltf::Node) -> DMat4 {
    match node.transform() {
        gltf::scene::Transform::Matrix { matrix } => {
            DMat4::from_cols_array_2d(&matrix.map(|c| c.map(f64::from)))
        }
        gltf::scene::Transform::Decomposed {
            translation,
            rotation,
            scale,
        } => {
            // Exporters write slightly unnormalized quaternions; an all-zero one (invalid) is
            // taken as no rotation rather than filling every position with NaN.
            let rotation = DVec4::from_array(rotation.map(f64::from))
                .try_normalize()
                .map_or(DQuat::IDENTITY, DQuat::from_vec4);
            DMat4::from_scale_rotation_translation(
                DVec3::from_array(scale.map(f64::from)),
                rotation,
                DVec3::from_array(translation.map(f64::from)),
            )
        }
    }
}
