//! A pipeline compiled for a device: frames to run, outputs to read back.

use std::path::PathBuf;

use image::RgbaImage;
use rgraph_core::file::LoadedGraph;
use rgraph_core::gpu::{read_rgba8, Executor, FrameReport, Gpu, Imports};
use rgraph_core::{CompiledGraph, Plan, ResourceId};
use rgraph_scene::analysis::Features as SceneFeatures;

use super::FrameError;

/// Made by [`Session::prepare`](super::Session::prepare) from a
/// [`Pipeline`](super::Pipeline); the executor's pool keeps the textures across frames, so
/// only the first frame allocates and uploads the scene.
pub struct Prepared<'s> {
    gpu: &'s Gpu,
    /// The pipeline's file.
    pub path: PathBuf,
    /// What the deferred plugins built their shader variants for.
    pub shader_features: SceneFeatures,
    compiled: CompiledGraph<LoadedGraph>,
    executor: Executor,
    /// The kept outputs and their resources, checked readable.
    outputs: Vec<(String, ResourceId)>,
}

impl<'s> Prepared<'s> {
    pub(super) fn new(
        gpu: &'s Gpu,
        path: PathBuf,
        shader_features: SceneFeatures,
        compiled: CompiledGraph<LoadedGraph>,
        executor: Executor,
        outputs: Vec<(String, ResourceId)>,
    ) -> Self {
        Prepared {
            gpu,
            path,
            shader_features,
            compiled,
            executor,
            outputs,
        }
    }

    /// The plan the frames run.
    pub fn plan(&self) -> &Plan {
        self.compiled.plan()
    }

    /// The pipeline's graph, as loaded.
    pub fn loaded(&self) -> &LoadedGraph {
        self.compiled.graph()
    }

    /// Whether a pass of the plan runs `plugin`'s passes (`"transparent"`, say).
    pub fn runs(&self, plugin: &str) -> bool {
        let loaded = self.loaded();
        self.plan()
            .passes
            .iter()
            .any(|p| loaded.plugin(&p.name) == Some(plugin))
    }

    /// Runs `frames` frames one after the other, each waited for, and reports each.
    pub fn run(&mut self, frames: usize) -> Result<Vec<FrameReport>, FrameError> {
        (0..frames)
            .map(|_| {
                self.executor
                    .execute(&mut self.compiled, &Imports::new())
                    .map_err(|source| FrameError::Execute {
                        pipeline: self.path.clone(),
                        source,
                    })
            })
            .collect()
    }

    /// The texture holding the last frame's `output` (one of the kept outputs): an
    /// `Rgba8UnormSrgb` or `Rgba8Unorm` texture with `COPY_SRC`, valid until the next frame.
    pub fn texture(&self, output: &str) -> Result<&wgpu::Texture, FrameError> {
        let unreadable = |found: &str| FrameError::unreadable(output, &self.path, found);
        let id = self
            .outputs
            .iter()
            .find(|(name, _)| name == output)
            .map(|(_, id)| *id)
            .ok_or_else(|| unreadable("not one of the outputs kept"))?;
        self.executor
            .texture(self.compiled.plan(), id)
            .ok_or_else(|| unreadable("not kept after the frame"))
    }

    /// The last frame's `output` (one of the kept outputs) as raw RGBA8 bytes (sRGB-encoded
    /// for sRGB formats), with any device error the readback raised outside the frame.
    pub fn read(&self, output: &str) -> Result<RgbaImage, FrameError> {
        let pipeline = &self.path;
        let unreadable = |found: &str| FrameError::unreadable(output, pipeline, found);
        let texture = self.texture(output)?;
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
