//! The recordings of the deferred passes (feature `gpu`), while they move into their
//! passes' modules.

pub(crate) mod light;
