//! `rgraph render`: one frame, headless, written as an 8-bit sRGB PNG.
//!
//! Stages, in the order that finds cheap mistakes before expensive work: the arguments,
//! the scene, the pipeline and its view, then the device, the compile for that device,
//! the frame, the readback and the PNG.

mod error;
mod output;
mod progress;
mod summary;
mod view;

use std::path::Path;
use std::sync::Arc;

use graph_core::file::{load_file, ErrorKind, FileErrors, LoadedGraph};
use graph_core::gpu::{read_rgba8, AdapterChoice, Executor, Gpu, Imports};
use graph_core::types::TextureFormat;
use graph_core::{CompileOptions, DeviceProfile, Origin, Plan};
use passes_deferred_msaa::scene::Scene;
use passes_deferred_msaa::{Host, Overrides};

use super::CommandError;
use crate::cli::RenderArgs;
use crate::registry::registry_for;
use error::RenderError;
use progress::Progress;

/// Renders and prints the written path on stdout (the only thing there).
pub fn run(args: &RenderArgs) -> Result<(), CommandError> {
    render(args).map_err(RenderError::into_command_error)?;
    println!("{}", args.out.display());
    Ok(())
}

fn render(args: &RenderArgs) -> Result<(), RenderError> {
    output::check(&args.out)?;
    let mut progress = Progress::new(7);

    progress.stage(format!("load scene {}", args.scene));
    let registry = registry_for(Some(host(args, &progress)?));

    progress.stage(format!("load pipeline {}", args.pipeline.display()));
    let mut loaded =
        load_file(&args.pipeline, &registry).map_err(|e| pipeline_error(&args.pipeline, e))?;
    view::select(&mut loaded, &args.view, &args.pipeline)?;
    let output = view::output_name(&args.view);

    let choice = AdapterChoice::resolve(args.adapter.as_deref());
    progress.stage(format!("open device ({choice})"));
    let gpu = Gpu::open(&choice)?;
    let profile = gpu.profile();
    check_size(args, &profile)?;

    progress.stage(format!("compile for {}", profile.name));
    let plan = loaded
        .compile(&CompileOptions {
            output_size: (args.width, args.height),
            profile,
        })
        .map_err(RenderError::Pipeline)?;
    let id = readable_output(&loaded, &plan, &output, &args.pipeline)?;
    no_imports(&plan, &args.pipeline)?;

    progress.stage("upload and render");
    let mut executor = Executor::new(&gpu);
    let report = executor
        .execute(&mut loaded.graph, &plan, &Imports::new())
        .map_err(|source| RenderError::Execute {
            pipeline: args.pipeline.clone(),
            source,
        })?;

    progress.stage(format!("read back \"{output}\""));
    let texture = executor.texture(&plan, id).ok_or_else(|| {
        RenderError::unreadable(&output, &args.pipeline, "not kept after the frame")
    })?;
    let texels = read_back(&gpu, texture, &output, &args.pipeline)?;

    progress.stage(format!("write {}", args.out.display()));
    output::write_png(&args.out, (texture.width(), texture.height()), &texels)?;
    drop(progress);
    eprintln!("{}", summary::text(&plan, &report));
    Ok(())
}

/// The scene and the overrides, for the deferred plugins. Scene statistics and the
/// loader's warnings go to stderr.
fn host(args: &RenderArgs, progress: &Progress) -> Result<Arc<Host>, RenderError> {
    let scene = Scene::load(&args.scene).map_err(RenderError::Scene)?;
    progress.note(format!("scene {}: {}", args.scene, scene.stats()));
    for warning in &scene.warnings {
        progress.note(format!("warning: {warning}"));
    }
    Ok(Arc::new(Host {
        scene: Arc::new(scene),
        overrides: Overrides {
            tonemap: args.tonemap.map(|t| t.name().to_string()),
            exposure: args.exposure,
        },
    }))
}

/// The output's texels, and any device error the readback raised outside the frame.
fn read_back(
    gpu: &Gpu,
    texture: &wgpu::Texture,
    output: &str,
    pipeline: &Path,
) -> Result<Vec<[u8; 4]>, RenderError> {
    let texels =
        read_rgba8(&gpu.device, &gpu.queue, texture).map_err(|source| RenderError::Readback {
            pipeline: pipeline.to_path_buf(),
            output: output.to_string(),
            source,
        })?;
    let late = gpu.take_errors();
    if !late.is_empty() {
        return Err(RenderError::LateDevice {
            pipeline: pipeline.to_path_buf(),
            messages: late.join("\n"),
        });
    }
    Ok(texels)
}

/// An unreadable file is an I/O problem (exit 2); anything else in it makes it invalid.
fn pipeline_error(path: &Path, errors: FileErrors) -> RenderError {
    let unreadable = errors.0.iter().find_map(|e| match &e.kind {
        ErrorKind::Unreadable { reason } if Path::new(&e.location.path) == path => {
            Some(reason.clone())
        }
        _ => None,
    });
    match unreadable {
        Some(reason) => RenderError::PipelineUnreadable {
            path: path.to_path_buf(),
            reason,
        },
        None => RenderError::Pipeline(errors),
    }
}

/// Both dimensions must fit the device, checked before any GPU work.
fn check_size(args: &RenderArgs, profile: &DeviceProfile) -> Result<(), RenderError> {
    let max = profile.limits.max_texture_dimension_2d;
    for (flag, value) in [("width", args.width), ("height", args.height)] {
        if value > max {
            return Err(RenderError::TooLarge {
                flag,
                value,
                max,
                adapter: profile.name.clone(),
            });
        }
    }
    Ok(())
}

/// The resource behind `output`, when it is an 8-bit RGBA texture the graph creates (the
/// executor keeps those for readback; imported ones belong to an engine the CLI is not).
fn readable_output(
    loaded: &LoadedGraph,
    plan: &Plan,
    output: &str,
    pipeline: &Path,
) -> Result<graph_core::ResourceId, RenderError> {
    let unreadable = |found: String| RenderError::unreadable(output, pipeline, found);
    let handle = loaded
        .names
        .get(output)
        .ok_or_else(|| unreadable("not declared".into()))?;
    let planned = plan.resource(handle.id());
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

/// The command line has no engine to bind imported resources from: say so before
/// executing, rather than with the executor's advice to call `Imports::texture`.
fn no_imports(plan: &Plan, pipeline: &Path) -> Result<(), RenderError> {
    let used = plan
        .resources
        .iter()
        .find(|r| r.origin == Origin::Imported && r.lifetime.is_some());
    match used {
        Some(import) => Err(RenderError::Imports {
            pipeline: pipeline.to_path_buf(),
            resource: import.name.clone(),
        }),
        None => Ok(()),
    }
}
