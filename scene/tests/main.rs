//! rgraph-scene's tests, one binary: scenes from glTF and the built-ins, the glTF sandbox
//! and limits, and the scene math the shaders share.

// Counts each thread's allocations: this binary's global allocator.
mod allocations;
mod common;

mod builtin_scale;
mod builtin_scenes;
mod clusters;
mod framing;
mod gltf_animation;
mod gltf_audit;
mod gltf_deform;
mod gltf_errors;
mod gltf_features;
mod gltf_fixtures;
mod gltf_instancing;
mod gltf_limits;
mod gltf_material_layers;
mod gltf_quantization;
mod gltf_sandbox;
mod gltf_spec_gloss;
mod robustness;
mod scene_math;
mod structure;
// The structure check rgraph-core's tests run, shared.
#[path = "../../graph-core/tests/structure_check.rs"]
mod structure_check;
