//! A pipeline compiled for a device: frames to run, outputs to read back.

use graph_core::gpu::{read_rgba8, Executor, FrameReport, Gpu, Imports};
use graph_core::{Plan, ResourceId};
use image::RgbaImage;
use passes_deferred_msaa::scene::AlphaMode;

use super::{FrameError, Pipeline};

/// Made by [`Session::prepare`](super::Session::prepare); the executor's pool keeps the
/// textures across frames, so only the first frame allocates and uploads the scene.
pub struct Prepared<'s> {
    gpu: &'s Gpu,
    pub pipeline: Pipeline,
    pub plan: Plan,
    executor: Executor,
    /// The kept outputs and their resources, checked readable.
    outputs: Vec<(String, ResourceId)>,
}

impl<'s> Prepared<'s> {
    pub(super) fn new(
        gpu: &'s Gpu,
        pipeline: Pipeline,
        plan: Plan,
        executor: Executor,
        outputs: Vec<(String, ResourceId)>,
    ) -> Self {
        Prepared {
            gpu,
            pipeline,
            plan,
            executor,
            outputs,
        }
    }

    /// Whether the scene has meshes with alpha BLEND materials that no pass of the plan
    /// draws: the opaque passes skip them, and only a `transparent` pass draws them, so a
    /// pipeline without one (or a view that culls it) leaves them out.
    pub fn blend_left_out(&self) -> bool {
        let scene = &self.pipeline.scene;
        let blended = scene.meshes.iter().any(|mesh| {
            scene
                .materials
                .get(mesh.material)
                .is_some_and(|m| m.alpha_mode == AlphaMode::Blend)
        });
        let loaded = &self.pipeline.loaded;
        blended
            && !self
                .plan
                .passes
                .iter()
                .any(|p| loaded.plugin(&p.name) == Some("transparent"))
    }

    /// Runs `frames` frames one after the other, each waited for, and reports each.
    pub fn run(&mut self, frames: usize) -> Result<Vec<FrameReport>, FrameError> {
        (0..frames)
            .map(|_| {
                self.executor
                    .execute(&mut self.pipeline.loaded.graph, &self.plan, &Imports::new())
                    .map_err(|source| FrameError::Execute {
                        pipeline: self.pipeline.path.clone(),
                        source,
                    })
            })
            .collect()
    }

    /// The last frame's `output` (one of the kept outputs) as raw RGBA8 bytes (sRGB-encoded
    /// for sRGB formats), with any device error the readback raised outside the frame.
    pub fn read(&self, output: &str) -> Result<RgbaImage, FrameError> {
        let pipeline = &self.pipeline.path;
        let unreadable = |found: &str| FrameError::unreadable(output, pipeline, found);
        let id = self
            .outputs
            .iter()
            .find(|(name, _)| name == output)
            .map(|(_, id)| *id)
            .ok_or_else(|| unreadable("not one of the outputs kept"))?;
        let texture = self
            .executor
            .texture(&self.plan, id)
            .ok_or_else(|| unreadable("not kept after the frame"))?;
        let texels = read_rgba8(&self.gpu.device, &self.gpu.queue, texture).map_err(|source| {
            FrameError::Readback {
                pipeline: pipeline.clone(),
                output: output.to_string(),
                source,
            }
        })?;
        let late = self.gpu.take_errors();
        if !late.is_empty() {
            return Err(FrameError::LateDevice {
                pipeline: pipeline.clone(),
                messages: late.join("\n"),
            });
        }
        let bytes = texels.into_flattened();
        RgbaImage::from_raw(texture.width(), texture.height(), bytes)
            .ok_or_else(|| unreadable("of a size its texels do not fill"))
    }
}
