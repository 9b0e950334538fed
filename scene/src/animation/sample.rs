//! Sampling an animation at a time into the meshes' world transforms.

use glam::DMat4;

use super::clip::{Animation, AnimationId, Keyframes};
use super::interpolate;
use crate::node_tree::{LocalTransform, MeshPlacement};
use crate::{Pose, Scene, SceneError};

impl Scene {
    /// The animation `spec` names: an animation's name, else its index. Fails with the
    /// names of those the scene has.
    pub fn find_animation(&self, spec: &str) -> Result<AnimationId, SceneError> {
        let by_name = self.animations.iter().position(|a| a.name == spec);
        let by_index = || spec.parse().ok().filter(|&i| i < self.animations.len());
        by_name
            .or_else(by_index)
            .map(AnimationId)
            .ok_or_else(|| SceneError::UnknownAnimation {
                scene: self.name.clone(),
                given: spec.to_owned(),
                available: match self.animations.is_empty() {
                    true => "none: the scene has no animations".to_owned(),
                    false => (self.animations.iter().enumerate())
                        .map(|(i, a)| format!("{i} \"{}\"", a.name))
                        .collect::<Vec<_>>()
                        .join(", "),
                },
            })
    }

    /// Every animation's id, in file order.
    pub fn animation_ids(&self) -> impl Iterator<Item = AnimationId> {
        (0..self.animations.len()).map(AnimationId)
    }

    /// The animation `id` names.
    pub fn animation(&self, id: AnimationId) -> &Animation {
        &self.animations[id.0]
    }

    /// The scene with `animation` at `time` seconds: each mesh's and each points-and-lines
    /// primitive's object-to-world transform, each skin's joints and each morphed mesh's
    /// weights, what a renderer's frame inputs take. Nodes and weights no channel drives
    /// keep their rest values, so at a time where every channel is at its rest value the
    /// result is [`Scene::rest_pose`].
    pub fn animated_pose(&self, animation: AnimationId, time: f64) -> Pose {
        let animation = self.animation(animation);
        let worlds = self.nodes.worlds(&animation.locals(self, time));
        let meshes = self.meshes.iter().map(|m| m.transform);
        let points_lines = self.points_lines.iter().map(|p| p.transform);
        Pose {
            transforms: placed(&self.nodes.meshes, &worlds, meshes),
            points_lines: placed(&self.nodes.points_lines, &worlds, points_lines),
            skins: self.skin_matrices(&worlds),
            morph_weights: animation.weights(self, time),
        }
    }
}

/// The object-to-world transforms `placements` give in the nodes' `worlds`, or `rest`
/// where the tree has no placements (the loader keeps none without animations or skins).
fn placed(
    placements: &[MeshPlacement],
    worlds: &[DMat4],
    rest: impl Iterator<Item = DMat4>,
) -> Vec<DMat4> {
    match placements.is_empty() {
        true => rest.collect(),
        false => placements.iter().map(|p| p.world(worlds)).collect(),
    }
}

impl Animation {
    /// Each node's local transform at `time`: its rest transform with the channels'
    /// sampled values in place of the properties they drive.
    fn locals(&self, scene: &Scene, time: f64) -> Vec<DMat4> {
        let mut locals: Vec<LocalTransform> = scene.nodes.nodes.iter().map(|n| n.rest).collect();
        for channel in &self.channels {
            // The loader refuses channels on nodes with a matrix.
            if let LocalTransform::Trs(trs) = &mut locals[channel.node.index()] {
                let (how, times) = (channel.interpolation, channel.times.as_slice());
                match &channel.values {
                    Keyframes::Translation(values) => {
                        trs.translation = interpolate::sample(how, times, values, time)
                    }
                    Keyframes::Rotation(values) => {
                        trs.rotation = interpolate::sample(how, times, values, time)
                    }
                    Keyframes::Scale(values) => {
                        trs.scale = interpolate::sample(how, times, values, time)
                    }
                    Keyframes::Weights(_) => {}
                }
            }
        }
        locals.iter().map(LocalTransform::matrix).collect()
    }

    /// Each deformation's morph weights at `time`: its defaults, replaced by the sampled
    /// weights of the channels driving the node that places its mesh.
    fn weights(&self, scene: &Scene, time: f64) -> Vec<Vec<f32>> {
        let mut weights = scene.default_weights();
        for channel in &self.channels {
            let Keyframes::Weights(targets) = &channel.values else {
                continue;
            };
            let (how, times) = (channel.interpolation, channel.times.as_slice());
            let sampled: Vec<f32> = (targets.iter())
                .map(|values| interpolate::sample(how, times, values, time) as f32)
                .collect();
            let placed = |d: &crate::Deformation| scene.nodes.meshes.get(d.mesh).map(|p| p.node);
            for (deformation, weights) in scene.deformations.iter().zip(&mut weights) {
                // glTF gives every primitive of a mesh as many targets; one that has
                // other than the channel's keeps its defaults rather than a misfit list.
                if placed(deformation) == Some(channel.node) && weights.len() == sampled.len() {
                    weights.clone_from(&sampled);
                }
            }
        }
        weights
    }
}
