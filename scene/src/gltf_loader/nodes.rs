//! The node hierarchy flattened into world transforms.

use std::path::Path;

use glam::DMat4;

use super::{instancing, world};
use crate::error::label;
use crate::node_tree::NodeId;
use crate::SceneError;

/// A node reached from a scene root, with its object-to-world transform.
pub(super) struct Placed<'a> {
    pub node: gltf::Node<'a>,
    pub world: DMat4,
    /// Its parent's index in the list [`flatten`] returns; `None` for a scene root.
    pub parent: Option<usize>,
    /// Its EXT_mesh_gpu_instancing attributes, checked but not read: its mesh is placed
    /// once per instance instead of once.
    pub instances: Option<instancing::Instances<'a>>,
}

/// Every node of `scene`, depth first, parents before children, siblings in file order (so
/// "the first camera in the scene" means the first in this order). `local` is each node's
/// transform relative to its parent, by index (see [`super::transforms`]); they are composed
/// in f64 so large translations survive. Iterative, so deep hierarchies cannot overflow the
/// stack.
///
/// A world transform beyond what a scene can hold is an error naming the node (see
/// [`world::check`]).
///
/// A node's EXT_mesh_gpu_instancing attributes are checked here too (see
/// [`instancing::declared`]), so that placements are counted before anything is read.
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
    let mut stack: Vec<(gltf::Node<'a>, DMat4, Option<usize>)> =
        scene.nodes().map(|n| (n, DMat4::IDENTITY, None)).collect();
    stack.reverse();
    let mut placed = Vec::new();
    while let Some((node, parent_world, parent)) = stack.pop() {
        if std::mem::replace(&mut seen[node.index()], true) {
            return Err(SceneError::NodeHierarchy {
                file: file.to_owned(),
                node: label("node", node.index(), node.name()),
            });
        }
        let world = parent_world * local[node.index()];
        world::check(file, &node, &world, "its")?;
        let instances = instancing::declared(file, document, &node)?;
        let children: Vec<_> = node.children().collect();
        let index = Some(placed.len());
        stack.extend(children.into_iter().rev().map(|c| (c, world, index)));
        placed.push(Placed {
            node,
            world,
            parent,
            instances,
        });
    }
    Ok(placed)
}

/// Each glTF node's id in the loaded scene's node tree, which numbers `placed` in order;
/// `None` for nodes the scene does not reach.
pub(super) fn ids(document: &gltf::Document, placed: &[Placed]) -> Vec<Option<NodeId>> {
    let mut ids = vec![None; document.nodes().len()];
    for (i, p) in placed.iter().enumerate() {
        // At most MAX_MESHES placements and a few more nodes: u32 holds them.
        ids[p.node.index()] = Some(NodeId(i as u32));
    }
    ids
}
