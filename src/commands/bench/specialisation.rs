//! What specialising a pipeline to its scene saves: the general plan (compiled as for a
//! scene using every feature) measured beside the scene's, wherever the two differ.

use rgraph_core::TextureShape;
use rgraph_passes::variant::plan_shader_variants;
use serde::Serialize;

use super::memory::Memory;
use super::stats::Spread;
use crate::frame::Prepared;

/// The general plan's figures beside the scene's. Only rows whose plans differ have
/// one, so a `null` means the scene uses everything the file's conditions test.
#[derive(Debug, Serialize)]
pub struct Specialisation {
    /// The features the scene's plan was compiled for, among those the file tests.
    pub features: Vec<String>,
    /// The shader variants the scene's plan builds (`rgraph explain --scene` lists them
    /// with the general ones they replace).
    pub shader_variants: Vec<String>,
    /// Executed passes of the scene's plan and of the general one.
    pub passes: usize,
    pub general_passes: usize,
    pub general_memory: Memory,
    /// `null` when the device has no timestamp queries.
    pub general_gpu_frame_ms: Option<Spread>,
    /// The scene's plan with the general shaders, which splits the time saved between
    /// the plan's changes and the shader variants. `null` when only one of the two
    /// differs from the general pipeline (it saved all there is), or without timestamps.
    pub plan_only_gpu_frame_ms: Option<Spread>,
}

/// What decides whether two plans of one file do different work: the passes they run,
/// the textures they allocate and the shader variants they build.
#[derive(Debug, PartialEq)]
pub struct PlanShape {
    passes: Vec<String>,
    textures: Vec<TextureShape>,
    memory: Memory,
    variants: Vec<String>,
}

impl PlanShape {
    pub fn of(prepared: &Prepared<'_>) -> PlanShape {
        let plan = prepared.plan();
        PlanShape {
            passes: plan.passes.iter().map(|p| p.name.clone()).collect(),
            textures: plan.textures.iter().map(|t| t.shape).collect(),
            memory: Memory::of(plan, &[]),
            variants: plan_shader_variants(&prepared.shader_features, plan, prepared.loaded())
                .into_iter()
                .map(|v| v.variant.to_string())
                .collect(),
        }
    }

    /// Whether both plans run the same passes on the same textures, whatever their
    /// shaders.
    pub fn same_plan(&self, other: &PlanShape) -> bool {
        (&self.passes, &self.textures) == (&other.passes, &other.textures)
    }

    pub fn passes(&self) -> usize {
        self.passes.len()
    }

    pub fn variants(&self) -> &[String] {
        &self.variants
    }
}
