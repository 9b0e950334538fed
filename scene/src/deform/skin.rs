//! Skins: joints whose transforms deform the vertices bound to them.

use glam::DMat4;

use crate::node_tree::NodeId;

/// The most joints a skin may have: JOINTS_0 names a joint with at most 16 bits, and each
/// joint is a 64-byte matrix per skinned mesh per frame on the device.
pub const MAX_JOINTS: usize = 1 << 16;

/// A glTF skin: the nodes whose world transforms deform the meshes bound to it.
///
/// Contract: `joints` and `inverse_binds` have one entry each per joint, 1 to
/// [`MAX_JOINTS`] of them, every joint a node of [`Scene::nodes`](crate::Scene::nodes).
#[derive(Clone, Debug, PartialEq)]
pub struct Skin {
    /// `skin INDEX "NAME"`, as errors and warnings name glTF skins.
    pub name: String,
    /// Its joints, in the order [`SkinWeights::joints`] numbers them.
    pub joints: Vec<NodeId>,
    /// Per joint, from the bind pose's space (where the mesh's vertices are) to the
    /// joint's: glTF's inverseBindMatrices, the identity where the file gives none. A
    /// joint's skin matrix is its world transform times this.
    pub inverse_binds: Vec<DMat4>,
}

/// How a mesh's vertices hang on a skin's joints: four joints and weights per vertex.
///
/// Contract: one entry per vertex of the mesh in each; every joint below the skin's joint
/// count; weights finite, non-negative and summing to 1 (the loader renormalises sums
/// within a few percent of 1 and refuses others).
#[derive(Clone, Debug, PartialEq)]
pub struct SkinWeights {
    /// Index into [`Scene::skins`](crate::Scene::skins).
    pub skin: usize,
    /// Per vertex, four indices into [`Skin::joints`].
    pub joints: Vec<[u16; 4]>,
    /// Per vertex, how much each of its four joints moves it.
    pub weights: Vec<[f32; 4]>,
}
