//! Each measured pipeline's plan as a page beside its images, `SCENE/PIPELINE.plan.html`
//! (linked from results.md): the plan that was timed, compiled for the scene on the
//! measured device, with its per-pass medians, as `rgraph explain --format html
//! --timings results.json` draws it.

use std::path::Path;

use rgraph_core::explain::page::{self, Page, PassTime, Setting, Timings};
use rgraph_core::Plan;

use super::figures::Figures;
use super::images::slug;
use super::machine::Adapter;
use super::measure::Setup;

/// The page's file name for the pipeline (row) called `pipeline`.
pub fn file_name(pipeline: &str) -> String {
    format!("{}.plan.html", slug(pipeline))
}

/// The page of `plan`, the scene plan of `pipeline` (a row's name, from `file`) measured
/// on `scene` with `figures`.
pub fn html(
    setup: &Setup,
    scene: &str,
    pipeline: &str,
    file: &Path,
    plan: &Plan,
    mut setting: Setting,
    figures: &Figures,
) -> String {
    setting.scene = Some(scene.to_owned());
    let (w, h) = setup.size;
    let timings = Timings {
        source: format!(
            "this bench: {pipeline} on {scene}, measured at {w}×{h} on {} (medians of {} \
             rounds of {} frames)",
            Adapter::of(&setup.session.gpu).name,
            setup.rounds,
            setup.frames
        ),
        gpu_frame_ms: figures.gpu_frame_ms.as_ref().map(|s| s.median),
        cpu_record_ms: figures.cpu_record_ms.as_ref().map(|s| s.median),
        passes: figures
            .passes
            .iter()
            .map(|p| PassTime {
                name: p.name.clone(),
                gpu_ms: p.gpu_ms.as_ref().map(|s| s.median),
                cpu_ms: p.cpu_ms.as_ref().map(|s| s.median),
            })
            .collect(),
    };
    page::html(&Page {
        title: file.display().to_string(),
        plan,
        setting,
        timings: Some(timings),
        compare: None,
    })
}
