//! `rgraph render`: one frame, headless, written as an 8-bit sRGB PNG.
//!
//! Stages, in the order that finds cheap mistakes before expensive work: the arguments,
//! the scene, the pipeline and its view, then the device, the compile for that device,
//! the frame, the readback and the PNG.

mod error;
mod output;
mod progress;
mod saturation;
mod summary;
mod view;

use std::sync::Arc;

use graph_core::gpu::AdapterChoice;
use passes_deferred_msaa::scene::{AlphaMode, Scene};
use passes_deferred_msaa::Overrides;

use super::CommandError;
use crate::cli::{AssetArgs, RenderArgs};
use crate::frame::{host, FrameError, Pipeline, Session, Specialise};
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
    let scene = load_scene(&args.scene, &args.assets, &progress)?;
    let overrides = Overrides {
        tonemap: args.tonemap.map(|t| t.name().to_string()),
        exposure: args.exposure,
    };

    progress.stage(format!("load pipeline {}", args.pipeline.display()));
    let output = view::output_name(&args.view);
    let specialise = match args.no_specialise {
        true => Specialise::General,
        false => Specialise::ToScene,
    };
    let host = host(scene, overrides);
    let params = args.samples.params();
    let pipeline = Pipeline::load(&args.pipeline, host, &[&output], specialise, &params)
        .map_err(|e| view::unknown(e, &args.view))?;

    let choice = AdapterChoice::resolve(args.adapter.as_deref());
    progress.stage(format!("open device ({choice})"));
    let session = Session::open(&choice)?;

    progress.stage(format!("compile for {}", session.profile.name));
    let blended = draws_blended(&pipeline.scene);
    let mut prepared = session.prepare(pipeline, (args.width, args.height))?;

    // The opaque passes skip BLEND meshes and only a `transparent` pass draws them; debug
    // views cull it on purpose, so only the final image can miss it.
    if args.view == view::FINAL && blended && !prepared.runs("transparent") {
        progress.note(format!(
            "warning: the scene has alpha BLEND materials, but {} has no `transparent` pass \
             to draw them: they are left out (pipelines/*.ron show how to add one)",
            args.pipeline.display()
        ));
    }

    progress.stage("upload and render");
    let report = prepared.run(1)?.remove(0);

    progress.stage(format!("read back \"{output}\""));
    let image = prepared.read(&output)?;
    if image.dimensions() != (args.width, args.height) {
        // A pipeline may give its output a fixed size: the flags then do nothing, and the
        // user should hear so rather than wonder why the PNG has another size.
        progress.note(format!(
            "warning: --width {} --height {} do not apply: {} gives \"{output}\" a fixed \
             size of {}x{}, which is what was written",
            args.width,
            args.height,
            args.pipeline.display(),
            image.width(),
            image.height()
        ));
    }

    if let Some(share) = saturation::blown_out(&image).filter(|_| output == "color") {
        progress.note(format!(
            "warning: {:.0}% of the lit pixels are saturated (a channel at 255): lower \
             --exposure, or let --exposure auto meter the frame",
            share * 100.0
        ));
    }

    progress.stage(format!("write {}", args.out.display()));
    output::write_png(&args.out, &image)?;
    drop(progress);
    let specialised = specialise == Specialise::ToScene;
    eprintln!("{}", summary::text(prepared.plan(), &report, specialised));
    Ok(())
}

/// Whether some mesh of `scene` has an alpha BLEND material.
fn draws_blended(scene: &Scene) -> bool {
    scene.meshes.iter().any(|mesh| {
        scene
            .materials
            .get(mesh.material)
            .is_some_and(|m| m.alpha_mode == AlphaMode::Blend)
    })
}

/// The scene; its statistics and the loader's warnings go to stderr.
fn load_scene(
    spec: &str,
    assets: &AssetArgs,
    progress: &Progress,
) -> Result<Arc<Scene>, FrameError> {
    let scene = assets.load(spec).map_err(FrameError::Scene)?;
    progress.note(format!("scene {spec}: {}", scene.stats()));
    for warning in &scene.warnings {
        progress.note(format!("warning: {warning}"));
    }
    Ok(Arc::new(scene))
}
