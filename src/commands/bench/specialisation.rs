//! What specialising a pipeline to its scene saves: the general plan (compiled as for a
//! scene using every feature) measured beside the scene's, wherever the two differ.

use graph_core::{Plan, TextureShape};
use serde::Serialize;

use super::memory::Memory;
use super::stats::Spread;

/// The general plan's figures beside the scene's. Only rows whose plans differ have
/// one, so a `null` means the scene uses everything the file's conditions test.
#[derive(Debug, Serialize)]
pub struct Specialisation {
    /// The features the scene's plan was compiled for, among those the file tests.
    pub features: Vec<String>,
    /// Executed passes of the scene's plan and of the general one.
    pub passes: usize,
    pub general_passes: usize,
    pub general_memory: Memory,
    /// `null` when the device has no timestamp queries.
    pub general_gpu_frame_ms: Option<Spread>,
}

/// What decides whether two plans of one file do different work: the passes they run
/// and the textures they allocate.
#[derive(Debug, PartialEq)]
pub struct PlanShape {
    passes: Vec<String>,
    textures: Vec<TextureShape>,
    memory: Memory,
}

impl PlanShape {
    pub fn of(plan: &Plan) -> PlanShape {
        PlanShape {
            passes: plan.passes.iter().map(|p| p.name.clone()).collect(),
            textures: plan.textures.iter().map(|t| t.shape).collect(),
            memory: Memory::of(plan),
        }
    }

    pub fn passes(&self) -> usize {
        self.passes.len()
    }
}
