//! What an animation is: channels of keyframes driving node properties.

use glam::{DQuat, DVec3};

use crate::node_tree::NodeId;

/// An animation of [`Scene::animations`](crate::Scene::animations), by index.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct AnimationId(pub(crate) usize);

impl AnimationId {
    /// Its index in [`Scene::animations`](crate::Scene::animations).
    pub fn index(self) -> usize {
        self.0
    }
}

/// One glTF animation: channels that play together.
#[derive(Clone, Debug, PartialEq)]
pub struct Animation {
    /// The file's name for it, else `animation INDEX`.
    pub name: String,
    /// Channels targeting the nodes of [`Scene::nodes`](crate::Scene::nodes), in file order (a later channel on
    /// the same node and property wins): their transforms, and the morph weights of the
    /// meshes they place. Channels of nodes outside the loaded scene are left out.
    pub channels: Vec<Channel>,
    /// The first key time of all channels, seconds (0 without channels).
    pub start: f64,
    /// The last key time of all channels, seconds (0 without channels).
    pub end: f64,
}

/// Keyframes driving one property of one node.
#[derive(Clone, Debug, PartialEq)]
pub struct Channel {
    /// The node it moves.
    pub node: NodeId,
    /// How values between keys are found.
    pub interpolation: Interpolation,
    /// Key times in seconds: finite, strictly increasing, at least one.
    pub times: Vec<f64>,
    /// The values: one per key, or three for [`Interpolation::CubicSpline`] (in-tangent,
    /// value, out-tangent).
    pub values: Keyframes,
}

/// glTF's sampler interpolations.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Interpolation {
    /// The previous key's value, held until the next key.
    Step,
    /// Linear between keys; rotations spherical, along the shorter arc.
    Linear,
    /// A cubic Hermite spline through the keys with their in- and out-tangents;
    /// rotations normalised after.
    CubicSpline,
}

/// The values of a channel, by the property they drive.
#[derive(Clone, Debug, PartialEq)]
pub enum Keyframes {
    /// Translations.
    Translation(Vec<DVec3>),
    /// Rotations (unit quaternions, tangents not).
    Rotation(Vec<DQuat>),
    /// Scales.
    Scale(Vec<DVec3>),
    /// Morph target weights of the meshes the node places: per target, one weight per
    /// key (three for [`Interpolation::CubicSpline`]).
    Weights(Vec<Vec<f64>>),
}
