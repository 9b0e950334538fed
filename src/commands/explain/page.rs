//! `rgraph explain --format html`: the plan as a self-contained page
//! (`rgraph_core::explain::page`), with a bench's times (`--timings`) and the differences
//! from another graph file's plan (`--compare`) or another scene's (`--compare-scene`).

use std::path::Path;

use rgraph_core::explain::page::{self, Against, Page, Parameter, Setting};
use rgraph_core::file::{GraphParams, LoadedGraph};
use rgraph_core::{CompileOptions, Features, Plan};
use rgraph_scene::analysis::Analysis;

use super::{analyse, compile, load, timings};
use crate::cli::{AssetArgs, ExplainArgs, Format, Samples};
use crate::commands::CommandError;

/// Refuses the page's flags with another format, where they would be ignored.
pub fn check_flags(format: Format, args: &ExplainArgs) -> Result<(), CommandError> {
    let given = [
        (args.timings.is_some(), "--timings"),
        (args.compare.is_some(), "--compare"),
        (args.compare_scene.is_some(), "--compare-scene"),
    ];
    match given.iter().find(|(set, _)| *set) {
        Some((_, flag)) if format != Format::Html => Err(CommandError::Usage(format!(
            "{flag} is for --format html (the page); the text format compares with the plan \
             for a scene using every feature when --scene is given"
        ))),
        _ => Ok(()),
    }
}

/// What the page of one explained plan is built from.
pub struct Explained<'a> {
    pub pipeline: &'a Path,
    pub loaded: &'a LoadedGraph,
    pub plan: &'a Plan,
    /// The scene as given and its analysis, when the plan is specialised to one.
    pub scene: Option<&'a (String, Analysis)>,
    pub options: &'a CompileOptions,
    pub samples: &'a Samples,
    pub assets: &'a AssetArgs,
}

/// The page of `explained`, with what `args` add.
pub fn html(explained: &Explained, args: &ExplainArgs) -> Result<String, CommandError> {
    let timings = args
        .timings
        .as_deref()
        .map(|path| {
            let scene = explained.scene.map(|(spec, _)| spec.as_str());
            timings::read(path, explained.pipeline, scene)
        })
        .transpose()?;
    let other = compared(explained, args)?;
    let setting = Setting {
        scene: explained.scene.map(|(spec, _)| spec.clone()),
        scene_features: explained.scene.map_or_else(Vec::new, |(_, analysis)| {
            analysis
                .features
                .names()
                .iter()
                .map(str::to_owned)
                .collect()
        }),
        ..parameters(explained.loaded, &explained.samples.params())
    };
    let page = Page {
        title: explained.pipeline.display().to_string(),
        plan: explained.plan,
        setting,
        timings,
        compare: other.as_ref().map(|(label, plan)| Against {
            label: label.clone(),
            plan,
        }),
    };
    Ok(page::html(&page))
}

/// The plan `--compare` and `--compare-scene` name, with its label: the other file
/// compiled for the same scene and parameters, or this file for the other scene.
fn compared(
    explained: &Explained,
    args: &ExplainArgs,
) -> Result<Option<(String, Plan)>, CommandError> {
    if args.compare.is_none() && args.compare_scene.is_none() {
        return Ok(None);
    }
    let file = args.compare.as_deref().unwrap_or(explained.pipeline);
    let other = args
        .compare
        .as_deref()
        .map(|other| load(other, explained.samples, &args.outputs, explained.options))
        .transpose()?;
    let loaded = other.as_ref().unwrap_or(explained.loaded);
    let scene = match &args.compare_scene {
        Some(spec) => Some(analyse(
            spec,
            explained.assets,
            explained.options.output_size,
        )?),
        None => explained.scene.cloned(),
    };
    let features = scene
        .as_ref()
        .map_or_else(Features::new, |(_, a)| a.features.names());
    let plan = compile(loaded, explained.options, &features, file)?;
    let label = match (&args.compare, &scene) {
        (Some(other), Some((spec, _))) => format!("{} on {spec}", other.display()),
        (Some(other), None) => other.display().to_string(),
        (None, Some((spec, _))) => format!("the plan for {spec}"),
        (None, None) => "the plan for no scene".to_owned(),
    };
    Ok(Some((label, plan)))
}

/// The file's parameters with the values `given` (the rest the file's defaults), as the
/// page shows them; the caller adds the scene.
pub fn parameters(loaded: &LoadedGraph, given: &GraphParams) -> Setting {
    Setting {
        parameters: loaded
            .params()
            .iter()
            .map(|(name, value)| Parameter {
                name: name.to_owned(),
                value,
                given: given.get(name).is_some(),
            })
            .collect(),
        ..Setting::default()
    }
}
