//! rgraph-passes' CPU tests, one binary: the crate's structure, and the normal encoding
//! its WGSL shares with the CPU. Its GPU tests, which need a device, are the root
//! package's (tests/).

mod extremes_normals;
mod structure;
// The structure check rgraph-core's tests run, shared.
#[path = "../../graph-core/tests/structure_check.rs"]
mod structure_check;
