//! A pose: what moves between frames, for every mesh, skin and morphed mesh at once.

use glam::DMat4;

use crate::Scene;

/// Where a scene's meshes, points and lines, joints and morph weights are in one frame: the
/// scene at rest ([`Scene::rest_pose`]) or an animation at a time
/// ([`Scene::animated_pose`]). A renderer's frame inputs take the four lists as they are.
#[derive(Clone, Debug, PartialEq)]
pub struct Pose {
    /// One object-to-world transform per mesh of [`Scene::meshes`], in its order.
    pub transforms: Vec<DMat4>,
    /// One object-to-world transform per primitive of [`Scene::points_lines`], in its
    /// order: where the nodes placing them are (points and lines are not deformed).
    pub points_lines: Vec<DMat4>,
    /// One list per skin of [`Scene::skins`], in its order: each joint's skin matrix, its
    /// world transform times its inverse bind matrix (world space; a mesh's skinning
    /// takes them into its object space with [`joints_in_object_space`](super::joints_in_object_space)).
    pub skins: Vec<Vec<DMat4>>,
    /// One list per deformation of [`Scene::deformations`], in its order: its morph
    /// targets' weights (empty for a deformation without morph targets).
    pub morph_weights: Vec<Vec<f32>>,
}

impl Scene {
    /// The scene as loaded: the meshes' and the points' and lines' own transforms, the
    /// joints at their nodes' rest transforms, the morph targets' default weights.
    pub fn rest_pose(&self) -> Pose {
        let locals: Vec<DMat4> = self.nodes.nodes.iter().map(|n| n.rest.matrix()).collect();
        Pose {
            transforms: self.meshes.iter().map(|m| m.transform).collect(),
            points_lines: self.points_lines.iter().map(|p| p.transform).collect(),
            skins: self.skin_matrices(&self.nodes.worlds(&locals)),
            morph_weights: self.default_weights(),
        }
    }

    /// Each skin's joints' skin matrices given each node's world transform.
    pub(crate) fn skin_matrices(&self, worlds: &[DMat4]) -> Vec<Vec<DMat4>> {
        (self.skins.iter())
            .map(|skin| {
                let joints = skin.joints.iter().zip(&skin.inverse_binds);
                joints
                    .map(|(joint, inverse_bind)| worlds[joint.index()] * *inverse_bind)
                    .collect()
            })
            .collect()
    }

    /// Each deformation's default morph weights (none without morph targets).
    pub(crate) fn default_weights(&self) -> Vec<Vec<f32>> {
        (self.deformations.iter())
            .map(|d| {
                d.morph
                    .as_ref()
                    .map_or_else(Vec::new, |m| m.weights.clone())
            })
            .collect()
    }
}
