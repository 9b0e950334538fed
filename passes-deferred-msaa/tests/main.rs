//! The deferred MSAA plugins' CPU tests, one binary: scenes from glTF and the built-ins,
//! and the math they share with the shaders.

mod common;

mod builtin_scenes;
mod extremes_normals;
mod framing;
mod gltf_audit;
mod gltf_errors;
mod gltf_features;
mod gltf_fixtures;
mod gltf_limits;
mod gltf_sandbox;
mod robustness;
mod scene_math;
mod structure;
// The structure check graph-core's tests run, shared.
#[path = "../../graph-core/tests/structure_check.rs"]
mod structure_check;
