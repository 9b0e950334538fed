//! Morph targets: per-vertex offsets a mesh blends by weights.

/// One morph target: offsets added to the rest vertices, times the target's weight.
///
/// Contract: each list is empty (the target does not move that attribute) or has one
/// entry per vertex of the mesh; every component finite.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MorphTarget {
    /// Object-space position offsets.
    pub positions: Vec<[f32; 3]>,
    /// Normal offsets (the result is renormalised).
    pub normals: Vec<[f32; 3]>,
    /// Tangent offsets, xyz (the bitangent sign stays).
    pub tangents: Vec<[f32; 3]>,
}

/// A mesh's morph targets and the weights it has where no animation or engine says
/// otherwise.
///
/// Contract: `weights` has one finite weight per target, and there is at least one target.
#[derive(Clone, Debug, PartialEq)]
pub struct MorphTargets {
    /// The targets, in the file's order.
    pub targets: Vec<MorphTarget>,
    /// The default weights: the placing node's `weights`, else the glTF mesh's, else 0.
    pub weights: Vec<f32>,
}
