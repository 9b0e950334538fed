//! The root package's tests, one binary: GPU tests on lavapipe (or the adapter
//! `RGRAPH_ADAPTER` names) and the `rgraph` command run as a user runs it.
//!
//! One binary rather than one per file: each test binary links wgpu and naga, and 36 of
//! them cost CI minutes of linking and gigabytes of disk.

mod browser_support;
// The builder-only example, whose frame tests/builder_example.rs checks (its `main` is not run).
#[allow(dead_code)]
#[path = "../examples/builder_only.rs"]
mod builder_only;
mod cli_support;
mod common;
mod deferred_support;
// The engine example, whose frame loop tests/engine_example.rs runs (its `main` is not).
#[allow(dead_code)]
#[path = "../examples/engine_integration.rs"]
mod engine_integration;
mod fuzz_support;
// rgraph-scene's glTF writer, for GPU tests of files the loader reads.
#[allow(dead_code)]
#[path = "../scene/tests/common/mod.rs"]
mod gltf_writer;

mod background;
mod background_fill;
mod baselines_errors;
mod baselines_forward;
mod baselines_reference;
mod baselines_resolve;
mod builder_example;
mod cli_anywhere;
mod cli_assets;
mod cli_bench;
mod cli_bench_motion;
mod cli_compare;
mod cli_render;
mod cli_render_animation;
mod cli_render_frames;
mod cli_render_samples;
mod cli_render_scale;
mod cli_trust;
mod cli_validate;
mod cli_view;
mod culling;
mod default_pipeline;
mod deferred_detectors;
mod deferred_environment;
mod deferred_exposure;
mod deferred_gltf;
mod deferred_lean;
mod deferred_lit;
mod deferred_materials;
mod deferred_sample_mask;
mod deferred_textures;
mod deferred_tiled;
mod deferred_unlit;
mod deferred_views;
mod deferred_volumes;
mod deferred_volumes_gpu;
mod deformation;
mod engine_example;
mod explain_page;
mod extremes_depth;
mod extremes_determinism;
mod extremes_far;
mod extremes_geometry;
mod extremes_hdr;
mod extremes_lights;
mod extremes_normals;
mod extremes_sizes;
mod extremes_thresholds;
mod extremes_volumes;
mod face_normals;
mod frame_inputs;
mod fuzz;
mod gpu_execute;
mod gpu_failures;
mod helper_loads;
mod instancing;
mod kept_pipelines;
mod light_prepass;
mod material_layers;
mod motion_vectors;
mod output_files;
mod page_browser;
mod particles;
mod pipeline_plans;
mod points_lines;
mod post_fxaa;
mod post_ssao;
mod shadows;
mod smooth_surfaces;
// Resident memory from /proc, glibc's live heap and its malloc arenas: Linux and glibc only.
#[cfg(all(target_os = "linux", target_env = "gnu"))]
mod soak;
mod specialise_analysis;
mod specialise_depth;
mod specialise_errors;
mod specialise_explain;
mod specialise_lights;
mod specialise_samples;
mod specialise_unlit;
mod specialise_variants;
mod temporal_aa;
mod texture_seams;
mod transparency;
mod vertex_ranges;
mod visibility;
