//! glTF animations: keyframed translations, rotations and scales of the nodes in
//! [`Scene::nodes`](crate::Scene::nodes), sampled at a time into the meshes' world transforms, which an engine
//! hands the renderer as a frame's inputs.
//!
//! Loading checks every sampler (see the glTF loader), so sampling cannot fail: times are
//! finite and strictly increasing, values finite, and counts match the interpolation.

mod clip;
mod interpolate;
mod motion;
mod sample;

pub use clip::{Animation, AnimationId, Channel, Interpolation, Keyframes};
pub(crate) use motion::swept_bounds;
