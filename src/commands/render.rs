//! `rgraph render`: one frame, headless, written as an 8-bit sRGB PNG; or `--frames N`
//! through one executor with the camera orbiting (`--orbit`) and the meshes posed by an
//! animation (`--animation`, `--time`), one PNG each.
//!
//! Stages, in the order that finds cheap mistakes before expensive work: the arguments,
//! the scene, the pipeline and its view, then the device, the compile for that device,
//! the frame, the readback and the PNG.

mod color_bytes;
pub(super) mod error;
mod layers;
pub(super) mod output;
mod pose_offset;
mod progress;
mod saturation;
mod sequence;
mod summary;
pub(super) mod view;

use std::sync::Arc;

use image::RgbaImage;
use rgraph_core::gpu::{resident_bytes, AdapterChoice, DeviceObjects};
use rgraph_passes::Overrides;
use rgraph_scene::analysis::Features as SceneFeatures;
use rgraph_scene::{AlphaMode, Scene, Topology};

use super::CommandError;
use crate::cli::{AssetArgs, RenderArgs};
use crate::frame::{host, FrameError, Pipeline, Session, Specialise};
use error::RenderError;
use progress::Progress;
use sequence::Sequence;

/// Renders and prints each written path on stdout (the only thing there), one a line.
pub fn run(args: &RenderArgs) -> Result<(), CommandError> {
    render(args).map_err(RenderError::into_command_error)
}

/// Renders, printing each PNG's path on stdout as soon as it is written: a sequence keeps
/// no list of its frames, which grew by about 95 bytes a frame (7.8 MiB over 100,000).
fn render(args: &RenderArgs) -> Result<(), RenderError> {
    let paths = output::FramePaths::new(&args.out, args.frames)?;
    sequence::check_time(args)?;
    // One frame reads back and writes as stages of its own; a sequence does both per
    // frame within its render stage, with a timing line each.
    let single = args.frames == 1;
    let mut progress = Progress::new(if single { 7 } else { 5 });

    progress.stage(format!("load scene {}", args.frame.scene));
    let scene = load_scene(&args.frame.scene, &args.frame.assets, &progress)?;
    let overrides = Overrides {
        tonemap: args.tonemap.map(|t| t.name().to_string()),
        exposure: args.exposure,
        background: args.frame.background,
        shadows: args.frame.shadows.settings(),
    };

    progress.stage(format!("load pipeline {}", args.frame.pipeline.display()));
    let output = view::output_name(&args.frame.view);
    let specialise = match args.no_specialise {
        true => Specialise::General,
        false => Specialise::ToScene,
    };
    let host = host(scene, overrides);
    let sequence = Sequence::new(&host, args)?;
    let params = args.frame.samples.params();
    let pipeline = Pipeline::load(
        &args.frame.pipeline,
        host.clone(),
        &[&output],
        specialise,
        &params,
    )
    .map_err(|e| view::unknown(e, &args.frame.view))?;

    let choice = AdapterChoice::resolve(args.frame.adapter.as_deref());
    progress.stage(format!("open device ({choice})"));
    let session = Session::open(&choice)?;

    progress.stage(format!("compile for {}", session.profile.name));
    let blended = draws_blended(&pipeline.scene);
    let environment = SceneFeatures::of(&pipeline.scene).environment;
    let particles = pipeline.scene.particles().count();
    let points_lines = points_and_segments(&pipeline.scene);
    let scene = pipeline.scene.clone();
    let mut prepared = session.prepare(pipeline, args.frame.size())?;

    // The opaque passes skip BLEND meshes and only a `transparent` pass draws them; debug
    // views cull it on purpose, so only the final image can miss it.
    if args.frame.view == view::FINAL && blended && !prepared.runs("transparent") {
        progress.note(format!(
            "warning: the scene has alpha BLEND materials, but {} has no `transparent` pass \
             to draw them: they are left out (pipelines/*.ron show how to add one)",
            args.frame.pipeline.display()
        ));
    }
    // The default lighting's environment shows behind the model where the pipeline
    // draws a background (a --background it cannot draw was refused above).
    if args.frame.view == view::FINAL
        && args.frame.background.is_none()
        && environment
        && !prepared.runs("background")
    {
        progress.note(format!(
            "note: {} draws no background, so the environment of the default lighting \
             does not show behind the model (pipelines/visibility_msaa_4x.ron draws it)",
            args.frame.pipeline.display()
        ));
    }
    // Likewise particles: only a `particles` pass draws them.
    if args.frame.view == view::FINAL && particles > 0 && !prepared.runs("particles") {
        progress.note(format!(
            "warning: the scene has {particles} particles, but {} has no `particles` pass \
             to draw them: they are left out (pipelines/particles_*.ron draw them)",
            args.frame.pipeline.display()
        ));
    }

    // A G-buffer stores the material layers only where its plan keeps their targets:
    // elsewhere they are left out of the opaque surfaces it shades.
    if args.frame.view == view::FINAL {
        let warnings = layers::unshaded(
            &scene,
            prepared.plan(),
            prepared.loaded(),
            &args.frame.pipeline,
        );
        for warning in warnings {
            progress.note(warning);
        }
    }
    // Likewise a deformed scene's pose offset, in any view that moves its points.
    if let Some(warning) =
        pose_offset::unposed(prepared.plan(), prepared.loaded(), &args.frame.pipeline)
    {
        progress.note(warning);
    }

    // And glTF points and lines: only a `points_lines` pass draws them.
    if args.frame.view == view::FINAL && points_lines != (0, 0) && !prepared.runs("points_lines") {
        let what = match points_lines {
            (points, 0) => format!("{points} points"),
            (0, segments) => format!("{segments} line segments"),
            (points, segments) => format!("{points} points and {segments} line segments"),
        };
        progress.note(format!(
            "warning: the scene has {what}, but {} has no `points_lines` pass to draw them: \
             they are left out (pipelines/parts/points_lines.ron draws them)",
            args.frame.pipeline.display()
        ));
    }

    progress.stage(match single {
        true => "upload and render".to_string(),
        false => sequence.describe(&host, args.frames, args.orbit),
    });
    let mut first = None;
    for index in 0..args.frames {
        // Frame 0's inputs are the scene's own unless an animation poses it.
        if index > 0 || args.animation.is_some() {
            host.set_frame(sequence.inputs(&host, index))?;
        }
        let report = prepared.run(1)?.remove(0);
        if single {
            progress.stage(format!("read back \"{output}\""));
        }
        let image = prepared.read(&output)?;
        if index == 0 {
            warn_about(&image, args, &output, &progress);
        }
        let path = paths.path(index);
        if single {
            progress.stage(format!("write {}", path.display()));
        }
        output::write_png(&path, &image)?;
        if !single {
            let device = DeviceObjects::alive(&session.gpu.device);
            let line = summary::frame_line(index, &report, resident_bytes(), &device);
            progress.note(line);
        }
        println!("{}", path.display());
        first.get_or_insert(report);
    }
    drop(progress);
    let specialised = specialise == Specialise::ToScene;
    if let Some(report) = first {
        eprintln!("{}", summary::text(prepared.plan(), &report, specialised));
    }
    Ok(())
}

/// Warnings the first frame's image earns: a size the flags did not set, and a blown-out
/// final image.
fn warn_about(image: &RgbaImage, args: &RenderArgs, output: &str, progress: &Progress) {
    if image.dimensions() != args.frame.size() {
        // A pipeline may give its output a fixed size: the flags then do nothing, and the
        // user should hear so rather than wonder why the PNG has another size.
        progress.note(format!(
            "warning: --width {} --height {} do not apply: {} gives \"{output}\" a fixed \
             size of {}x{}, which is what was written",
            args.frame.width,
            args.frame.height,
            args.frame.pipeline.display(),
            image.width(),
            image.height()
        ));
    }
    if let Some(share) = saturation::blown_out(image).filter(|_| output == "color") {
        progress.note(format!(
            "warning: {:.0}% of the lit pixels are saturated (a channel at 255): lower \
             --exposure, or let --exposure auto meter the frame",
            share * 100.0
        ));
    }
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

/// The scene; its statistics and the loader's warnings go to stderr, each warning after
/// the file's name as a compiler's do (`FILE: warning: ...`).
fn load_scene(
    spec: &str,
    assets: &AssetArgs,
    progress: &Progress,
) -> Result<Arc<Scene>, FrameError> {
    let scene = assets.load(spec).map_err(FrameError::Scene)?;
    progress.note(format!("scene {spec}: {}", scene.stats()));
    for warning in AssetArgs::warnings(spec, &scene) {
        progress.note(warning);
    }
    Ok(Arc::new(scene))
}

/// How many points and line segments `scene` holds.
fn points_and_segments(scene: &Scene) -> (usize, usize) {
    scene
        .points_lines
        .iter()
        .fold((0, 0), |(points, segments), p| match p.topology {
            Topology::Points => (points + p.indices.len(), segments),
            Topology::Lines => (points, segments + p.indices.len() / 2),
        })
}
