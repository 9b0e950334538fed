//! Meshes whose vertices move between frames: glTF skins (each vertex blended from up to
//! eight joints' transforms) and morph targets (each vertex offset by weighted deltas).
//!
//! The scene keeps each deformed mesh's rest vertices ([`Mesh::vertices`](crate::Mesh)) and
//! what deforms them ([`Deformation`]); a [`Pose`] says where the joints are and what the
//! weights are for one frame ([`Scene::rest_pose`](crate::Scene::rest_pose),
//! [`Scene::animated_pose`](crate::Scene::animated_pose)). The renderer deforms on the
//! GPU; [`Deformation::deform`] does the same on the CPU, for references and for engines
//! that need the positions (picking, physics), and [`Reach`] bounds the result without
//! deforming every vertex.

mod deformation;
mod morph;
mod pose;
mod reach;
mod skin;

pub use deformation::{joints_in_object_space, Deformation};
pub use morph::{MorphTarget, MorphTargets};
pub use pose::Pose;
pub use reach::Reach;
pub use skin::{Influences, Skin, SkinWeights, MAX_JOINTS};
