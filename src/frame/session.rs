//! An open device, and pipelines compiled for it.

use std::path::Path;

use rgraph_core::file::LoadedGraph;
use rgraph_core::gpu::{AdapterChoice, Executor, Gpu};
use rgraph_core::types::TextureFormat;
use rgraph_core::{CompileOptions, CompiledGraph, DeviceProfile, Origin, Plan, ResourceId};

use rgraph_passes::Background;

use super::{FrameError, Pipeline, Prepared};

/// The device every frame of a command runs on, and what it can do.
pub struct Session {
    pub gpu: Gpu,
    pub profile: DeviceProfile,
}

impl Session {
    pub fn open(choice: &AdapterChoice) -> Result<Self, FrameError> {
        let gpu = Gpu::open(choice)?;
        let profile = gpu.profile();
        Ok(Session { gpu, profile })
    }

    /// Compiles `pipeline` for this device at `size` and its features, and checks,
    /// before any GPU work, that the command line can run it: nothing imported, every
    /// kept output made for these features and readable.
    pub fn prepare(
        &self,
        pipeline: Pipeline,
        size: (u32, u32),
    ) -> Result<Prepared<'_>, FrameError> {
        self.check_size(size)?;
        self.check_textures(&pipeline)?;
        let options = CompileOptions {
            output_size: size,
            profile: self.profile.clone(),
        };
        let Pipeline {
            path,
            loaded,
            outputs,
            features,
            shader_features,
            background,
            ..
        } = pipeline;
        let compiled = CompiledGraph::new_for(loaded, &options, &features.names())
            .map_err(FrameError::Pipeline)?;
        no_imports(compiled.plan(), &path)?;
        metered(&compiled, features.auto_exposure, &path)?;
        if let Some(background) = background {
            backgrounded(&compiled, background, &path)?;
        }
        let outputs = outputs
            .iter()
            .map(|o| {
                let id = readable_output(compiled.graph(), compiled.plan(), o, &path)?;
                Ok((o.clone(), id))
            })
            .collect::<Result<_, FrameError>>()?;
        Ok(Prepared::new(
            &self.gpu,
            path,
            shader_features,
            compiled,
            Executor::new(&self.gpu),
            outputs,
        ))
    }

    /// Every scene texture must fit the device: checked before anything is uploaded, so
    /// the error names the texture instead of the pass whose upload failed.
    fn check_textures(&self, pipeline: &Pipeline) -> Result<(), FrameError> {
        let max = self.profile.limits.max_texture_dimension_2d;
        match pipeline
            .scene
            .textures
            .iter()
            .find(|t| t.width > max || t.height > max)
        {
            Some(texture) => Err(FrameError::SceneTextureTooLarge {
                scene: pipeline.scene.name.clone(),
                texture: texture.name.clone(),
                width: texture.width,
                height: texture.height,
                max,
                adapter: self.profile.name.clone(),
            }),
            None => Ok(()),
        }
    }

    /// Both dimensions must fit the device.
    fn check_size(&self, (width, height): (u32, u32)) -> Result<(), FrameError> {
        let max = self.profile.limits.max_texture_dimension_2d;
        for (flag, value) in [("width", width), ("height", height)] {
            if value > max {
                return Err(FrameError::TooLarge {
                    flag,
                    value,
                    max,
                    adapter: self.profile.name.clone(),
                });
            }
        }
        Ok(())
    }
}

/// The resource behind `output`, when it is an 8-bit RGBA texture the graph creates (the
/// executor keeps those for readback; imported ones belong to an engine the CLI is not).
fn readable_output(
    loaded: &LoadedGraph,
    plan: &Plan,
    output: &str,
    pipeline: &Path,
) -> Result<ResourceId, FrameError> {
    let unreadable = |found: String| FrameError::unreadable(output, pipeline, found);
    let handle = loaded
        .names
        .get(output)
        .ok_or_else(|| unreadable("not declared".into()))?;
    let planned = plan.resource(handle.id());
    if let Some(why) = &planned.culled {
        // Kept outputs are never culled as unneeded: a condition dropped this one.
        return Err(FrameError::NotForScene {
            output: output.to_string(),
            pipeline: pipeline.to_path_buf(),
            why: why.clone(),
            features: match plan.features.is_empty() {
                true => "none the file tests".into(),
                false => plan.features.join(", "),
            },
        });
    }
    let shape = planned
        .texture
        .ok_or_else(|| unreadable("a buffer".into()))?;
    if planned.origin == Origin::Imported {
        return Err(unreadable("an imported texture".into()));
    }
    match shape.format {
        TextureFormat::Rgba8UnormSrgb | TextureFormat::Rgba8Unorm if shape.samples == 1 => {
            Ok(handle.id())
        }
        format => Err(unreadable(format!(
            "{format:?} with {} sample(s)",
            shape.samples
        ))),
    }
}

/// Auto exposure needs a pass that meters: a file without one would tone map with its
/// fixed exposure, silently.
fn metered(
    compiled: &CompiledGraph<LoadedGraph>,
    auto_exposure: bool,
    pipeline: &Path,
) -> Result<(), FrameError> {
    let metering =
        |p: &rgraph_core::PlannedPass| compiled.graph().plugin(&p.name) == Some("auto_exposure");
    match auto_exposure && !compiled.plan().passes.iter().any(metering) {
        true => Err(FrameError::NoMetering {
            pipeline: pipeline.to_path_buf(),
        }),
        false => Ok(()),
    }
}

/// A background asked for needs a pass that draws it: a file without one would show its
/// own (black), silently.
fn backgrounded(
    compiled: &CompiledGraph<LoadedGraph>,
    background: Background,
    pipeline: &Path,
) -> Result<(), FrameError> {
    let drawing =
        |p: &rgraph_core::PlannedPass| compiled.graph().plugin(&p.name) == Some("background");
    match compiled.plan().passes.iter().any(drawing) {
        true => Ok(()),
        false => Err(FrameError::NoBackground {
            pipeline: pipeline.to_path_buf(),
            background: background_flag(background),
        }),
    }
}

/// `background` as `--background` spells it.
pub fn background_flag(background: Background) -> String {
    match background {
        Background::Environment => "environment".into(),
        Background::Color([r, g, b]) => format!("color:{r},{g},{b}"),
        Background::Transparent => "transparent".into(),
    }
}

/// The command line has no engine to bind imported resources from: say so before
/// executing, rather than with the executor's advice to call `Imports::texture`.
fn no_imports(plan: &Plan, pipeline: &Path) -> Result<(), FrameError> {
    let used = plan
        .resources
        .iter()
        .find(|r| r.origin == Origin::Imported && r.lifetime.is_some());
    match used {
        Some(import) => Err(FrameError::Imports {
            pipeline: pipeline.to_path_buf(),
            resource: import.name.clone(),
        }),
        None => Ok(()),
    }
}
