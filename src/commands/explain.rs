//! `rgraph explain`: the compiled plan of a graph file, for people or tools, optionally
//! specialised to a scene.

pub mod page;
mod timings;
mod variants;

use std::path::Path;

use rgraph_core::explain;
use rgraph_core::file::{load_file_with, FileErrors, LoadedGraph};
use rgraph_core::{CompileOptions, Features, Plan};
use rgraph_passes::{Overrides, Shadows};
use rgraph_scene::analysis::{Analysis, Features as SceneFeatures, SHALLOW_STEP};
use rgraph_scene::SceneError;

use super::target::compile_options;
use super::{write_atomically, CommandError};
use crate::cli::{AssetArgs, ExplainArgs, Format, Samples, Target};
use crate::registry::registry;

pub fn run(
    pipeline: &Path,
    scene: Option<&str>,
    format: Format,
    target: &Target,
    samples: &Samples,
    assets: &AssetArgs,
    page_args: &ExplainArgs,
) -> Result<(), CommandError> {
    page::check_flags(format, page_args)?;
    let options = compile_options(target)?;
    let loaded = load(pipeline, samples, &page_args.outputs, &options)?;
    let mut analysis = scene
        .map(|spec| analyse(spec, assets, options.output_size))
        .transpose()?;
    if let Some((_, analysis)) = &mut analysis {
        // What `render` runs with no override but --shadows: under an environment, the
        // background passes too.
        let overrides = Overrides {
            shadows: Shadows {
                filter: page_args.shadows,
                ..Shadows::default()
            },
            ..Overrides::default()
        };
        let environment = analysis.features.environment;
        analysis.features = overrides.applied_to(analysis.features, environment);
    }
    let features = analysis
        .as_ref()
        .map_or_else(Features::new, |(_, a)| a.features.names());
    let plan = compile(&loaded, &options, &features, pipeline)?;
    let text = match format {
        Format::Text => format!("{}{}", parameters(&loaded, samples), explain::text(&plan)),
        Format::Dot => explain::dot(&plan),
        Format::Json => explain::json(&plan),
        Format::Html => page::html(
            &page::Explained {
                pipeline,
                loaded: &loaded,
                plan: &plan,
                scene: analysis.as_ref(),
                options: &options,
                samples,
                assets,
            },
            page_args,
        )?,
    };
    let output = match (&analysis, format) {
        (Some((spec, analysis)), Format::Text) => {
            // The plan for a scene using everything: what the file does unspecialised.
            let general = compile(
                &loaded,
                &options,
                &SceneFeatures::general().names(),
                pipeline,
            )?;
            format!(
                "{}\n{text}\n{}\n{}",
                describe(spec, analysis, &options),
                explain::compare(&plan, &general, "a scene using every feature"),
                variants::text(&plan, &loaded, &analysis.features)
            )
        }
        _ => text,
    };
    match &page_args.out {
        Some(path) => write_atomically(path, output.as_bytes()),
        None => {
            print!("{output}");
            Ok(())
        }
    }
}

/// The file's parameters and the values this plan was compiled with, as a first line (none
/// for a file without parameters).
fn parameters(loaded: &LoadedGraph, samples: &Samples) -> String {
    let given = samples.params();
    let values: Vec<String> = loaded
        .params()
        .iter()
        .map(|(name, value)| match given.get(name) {
            Some(_) => format!("{name} = {value} (given)"),
            None => format!("{name} = {value} (the file's default)"),
        })
        .collect();
    match values.is_empty() {
        true => String::new(),
        false => format!("parameters: {}\n", values.join(", ")),
    }
}

/// The graph file with the values `samples` gives its parameters, exporting only
/// `outputs` (all it exports when empty), validated as `validate` would.
fn load(
    pipeline: &Path,
    samples: &Samples,
    outputs: &[String],
    options: &CompileOptions,
) -> Result<LoadedGraph, CommandError> {
    let mut loaded = load_file_with(pipeline, &registry(), &samples.params())
        .map_err(|e| invalid(pipeline, e))?;
    // Checked as `validate` checks it, so a file explain shows is one validate accepts:
    // an error under a condition off by default is found too.
    loaded.validate(options).map_err(|e| invalid(pipeline, e))?;
    if !outputs.is_empty() {
        let names: Vec<&str> = outputs.iter().map(String::as_str).collect();
        loaded
            .keep_outputs(&names)
            .map_err(|e| CommandError::Usage(format!("--output: {e} in {}", pipeline.display())))?;
    }
    Ok(loaded)
}

fn compile(
    loaded: &LoadedGraph,
    options: &CompileOptions,
    features: &Features,
    pipeline: &Path,
) -> Result<Plan, CommandError> {
    loaded
        .compile_for(options, features)
        .map_err(|e| invalid(pipeline, e))
}

/// The file's errors go to stderr, so stdout (piped into `dot` or a JSON reader) only ever
/// holds a plan. A file that cannot be read at all is an I/O error (exit 2), as in
/// `validate`; one that is wrong exits 1.
fn invalid(pipeline: &Path, errors: FileErrors) -> CommandError {
    eprintln!("{errors}");
    if errors.is_unreadable(pipeline) {
        return CommandError::Usage(format!("cannot read {}", pipeline.display()));
    }
    CommandError::Invalid(format!("{} is invalid", pipeline.display()))
}

fn analyse(
    spec: &str,
    assets: &AssetArgs,
    output: (u32, u32),
) -> Result<(String, Analysis), CommandError> {
    let scene = assets.load(spec).map_err(|e| {
        eprintln!("error: scene {spec}: {e}");
        let message = format!("scene {spec} cannot be loaded");
        // As `render` and `validate`: a file that cannot be read is an I/O error.
        match e {
            SceneError::Io { .. } => CommandError::Usage(message),
            _ => CommandError::Invalid(message),
        }
    })?;
    for warning in AssetArgs::warnings(spec, &scene) {
        eprintln!("{warning}");
    }
    Ok((spec.to_owned(), Analysis::of(&scene, output)))
}

/// What analysis found, as the first lines of the report.
fn describe(spec: &str, analysis: &Analysis, options: &CompileOptions) -> String {
    let (w, h) = options.output_size;
    let depth = analysis.depth.map_or_else(
        || "no geometry between the camera's planes".to_owned(),
        |d| {
            format!(
                "depth {:.3} .. {:.3} (far/near {:.1})",
                d.near,
                d.far,
                d.ratio()
            )
        },
    );
    let detail = analysis.smallest.as_ref().map_or_else(
        || "no visible edge".to_owned(),
        |s| format!("smallest edge {:.2} px at {w}x{h} ({})", s.pixels, s.mesh),
    );
    // The depth decision: whether 24-bit unorm depth with standard Z resolves the scene
    // (`shallow_depth`), and by how much.
    let depth_format = analysis.unorm24_step.map_or_else(
        || "depth format: as declared (nothing to depth-test)".to_owned(),
        |step| {
            let (verdict, outcome) = match analysis.features.shallow_depth {
                true => (
                    "within",
                    "shallow_depth, 24-bit unorm depth with standard Z",
                ),
                false => ("beyond", "float depth with reversed-Z, as declared"),
            };
            format!(
                "depth format: a 24-bit unorm step is {step:.1e} of the distance, {verdict} \
                 {SHALLOW_STEP:.1e}: {outcome}"
            )
        },
    );
    format!(
        "scene {spec}: features {}\n{depth}; {detail}\n{depth_format}\n",
        analysis.features.names()
    )
}
