//! rgraph-core's tests, one binary: compiling graphs built in code and loaded from RON,
//! and the properties every compiled plan keeps.

mod common;
mod ron_support;

mod compiled;
mod conditional_formats;
mod conditions;
mod conditions_file;
mod cull;
mod history;
mod history_gpu;
mod lifetimes;
mod load_store;
mod memory;
mod optional_reads;
mod order;
mod plugin_pass;
mod properties;
mod ron_bindings;
mod ron_errors;
mod ron_names;
mod ron_params;
mod ron_parts;
mod ron_presets;
mod ron_roundtrip;
mod ron_sandbox;
mod ron_scale;
mod ron_validate;
mod structure;
mod structure_check;
mod usage;
mod validate_attachments;
mod validate_resources;
mod validate_roles;
mod validate_versions;
