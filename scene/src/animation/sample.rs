//! Sampling an animation at a time into the meshes' world transforms.

use glam::DMat4;

use super::clip::{Animation, AnimationId, Keyframes};
use super::interpolate;
use crate::node_tree::LocalTransform;
use crate::{Scene, SceneError};

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

    /// Each mesh's object-to-world transform with `animation` at `time` seconds, in the
    /// order of [`Scene::meshes`]: what `FrameInputs::transforms` takes. Nodes no channel
    /// drives keep their rest transforms, so at a time where every channel is at its rest
    /// value the result equals the meshes' own transforms.
    pub fn animated_transforms(&self, animation: AnimationId, time: f64) -> Vec<DMat4> {
        let locals = self.animation(animation).locals(self, time);
        let worlds = self.nodes.worlds(&locals);
        self.nodes.mesh_transforms(&worlds)
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
                }
            }
        }
        locals.iter().map(LocalTransform::matrix).collect()
    }
}
