//! Skins: joints whose transforms deform the vertices bound to them.

use glam::DMat4;

use crate::node_tree::NodeId;

/// The most joints a skin may have: JOINTS_n names a joint with at most 16 bits, and each
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
    /// Its joints, in the order [`Influences::joints`] numbers them.
    pub joints: Vec<NodeId>,
    /// Per joint, from the bind pose's space (where the mesh's vertices are) to the
    /// joint's: glTF's inverseBindMatrices, the identity where the file gives none. A
    /// joint's skin matrix is its world transform times this.
    pub inverse_binds: Vec<DMat4>,
}

/// How a mesh's vertices hang on a skin's joints: four joints and weights per vertex, or
/// eight for a glTF primitive with a second set (JOINTS_1, WEIGHTS_1).
///
/// Contract: one entry per vertex of the mesh in each list of each set; every joint below
/// the skin's joint count; weights finite and non-negative, a vertex's (over both sets)
/// summing to 1 (the loader renormalises sums within a few percent of 1 and refuses
/// others).
#[derive(Clone, Debug, PartialEq)]
pub struct SkinWeights {
    /// Index into [`Scene::skins`](crate::Scene::skins).
    pub skin: usize,
    /// Each vertex's first four joints and weights (JOINTS_0, WEIGHTS_0).
    pub first: Influences,
    /// Each vertex's fifth to eighth (JOINTS_1, WEIGHTS_1), for a mesh with more than four
    /// influences per vertex; `None` otherwise, which then keeps and uploads nothing more.
    pub second: Option<Influences>,
}

/// One set of four influences per vertex: glTF's JOINTS_n and WEIGHTS_n.
#[derive(Clone, Debug, PartialEq)]
pub struct Influences {
    /// Per vertex, four indices into [`Skin::joints`].
    pub joints: Vec<[u16; 4]>,
    /// Per vertex, how much each of its four joints moves it.
    pub weights: Vec<[f32; 4]>,
}

impl SkinWeights {
    /// Vertex `vertex`'s joints and their weights: four, or eight with a second set.
    pub fn influences(&self, vertex: usize) -> impl Iterator<Item = (u16, f32)> + '_ {
        let set = move |set: &Influences| set.joints[vertex].into_iter().zip(set.weights[vertex]);
        (std::iter::once(&self.first).chain(&self.second)).flat_map(set)
    }
}
