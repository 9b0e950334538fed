//! The node hierarchy that places a glTF file's meshes, kept so that animations can move
//! it after loading.

use glam::{DMat4, DQuat, DVec3};

/// A node of [`NodeTree::nodes`], by index: what animation channels target.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct NodeId(pub(crate) u32);

impl NodeId {
    /// Its index in [`NodeTree::nodes`].
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

/// A node's transform relative to its parent, as the file writes it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LocalTransform {
    /// A matrix: such a node cannot be animated (glTF allows only TRS on animated nodes).
    Matrix(DMat4),
    /// Translation, rotation and scale, which animation channels replace one by one.
    Trs(Trs),
}

/// Translation, rotation (unit quaternion) and scale, applied scale first.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Trs {
    /// Translation.
    pub translation: DVec3,
    /// Rotation, a unit quaternion.
    pub rotation: DQuat,
    /// Scale per axis.
    pub scale: DVec3,
}

impl Trs {
    /// No translation, no rotation, unit scale.
    pub const IDENTITY: Trs = Trs {
        translation: DVec3::ZERO,
        rotation: DQuat::IDENTITY,
        scale: DVec3::ONE,
    };

    /// As a matrix: translation * rotation * scale.
    pub fn matrix(&self) -> DMat4 {
        DMat4::from_scale_rotation_translation(self.scale, self.rotation, self.translation)
    }
}

impl LocalTransform {
    /// As a matrix.
    pub fn matrix(&self) -> DMat4 {
        match self {
            LocalTransform::Matrix(matrix) => *matrix,
            LocalTransform::Trs(trs) => trs.matrix(),
        }
    }
}

/// One node of the tree.
#[derive(Clone, Debug, PartialEq)]
pub struct Node {
    /// `node INDEX "NAME"`, as errors and warnings name glTF nodes.
    pub name: String,
    /// Its parent, which comes before it in [`NodeTree::nodes`]; `None` for a root.
    pub parent: Option<NodeId>,
    /// Its transform at rest: what it is where no animation channel says otherwise.
    pub rest: LocalTransform,
}

/// Where a mesh, or a primitive of points or lines, of the scene hangs in the tree.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeshPlacement {
    /// The node placing it.
    pub node: NodeId,
    /// From the mesh's object space to the node's: the identity, or an
    /// EXT_mesh_gpu_instancing instance's transform.
    pub offset: DMat4,
}

impl MeshPlacement {
    /// Its object-to-world transform given each node's world transform.
    pub fn world(&self, worlds: &[DMat4]) -> DMat4 {
        worlds[self.node.index()] * self.offset
    }
}

/// The nodes reached from the loaded glTF scene, parents before children, and where each
/// mesh of `Scene::meshes` and each primitive of `Scene::points_lines` hangs. Empty for
/// built-in scenes and for files without animations or skins, which have nothing to move.
///
/// Contract: every `parent` precedes its child; `meshes` is empty or has one placement per
/// mesh of the scene, in its order, and `points_lines` likewise per points-and-lines
/// primitive; at rest `world(node) * offset` is the placed one's `transform` exactly (the
/// loader composes it the same way).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct NodeTree {
    /// Parents before children.
    pub nodes: Vec<Node>,
    /// One per mesh of the scene, or none.
    pub meshes: Vec<MeshPlacement>,
    /// One per primitive of `Scene::points_lines`, or none.
    pub points_lines: Vec<MeshPlacement>,
}

impl NodeTree {
    /// Each node's world transform given each node's local one (`locals[i]` for
    /// `nodes[i]`): parents are composed first, in f64, as the loader does.
    pub fn worlds(&self, locals: &[DMat4]) -> Vec<DMat4> {
        let mut worlds: Vec<DMat4> = Vec::with_capacity(self.nodes.len());
        for (node, local) in self.nodes.iter().zip(locals) {
            let world = match node.parent {
                Some(parent) => worlds[parent.index()] * *local,
                None => *local,
            };
            worlds.push(world);
        }
        worlds
    }
}
