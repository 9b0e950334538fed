//! One scene of a bench: its reference, edge pixels and unique-surface bound, then every
//! pipeline measured, compared with the reference, and its images written.

use std::path::Path;
use std::sync::Arc;

use rgraph_passes::{Host, Overrides};
use rgraph_scene::Scene;

use super::candidates::Candidate;
use super::error::{BenchError, RowError};
use super::figures::Figures;
use super::image_error::compare;
use super::images::SceneImages;
use super::measure::{About, Closed, Measured, Setup};
use super::plan_page;
use super::progress::Progress;
use super::reference::{Reference, SceneReference};
use super::results::{Row, SceneSize, SceneSummary};
use super::rounds::{interleave, RoundLog, Timed};
use super::surfaces;
use crate::frame::{host, FrameError, Prepared};

/// Every pipeline on the scene `spec`, its rounds appended to `log`. When `out` is given
/// (outside sweeps), also the images under it and the unique-surface bound. A scene that
/// fails to load is one error row; a pipeline that fails is an error row and the others
/// go on. Only writing images fails the whole bench.
pub fn bench_scene(
    setup: &Setup,
    spec: &str,
    pipelines: &[Candidate],
    reference: Option<&Reference>,
    out: Option<&Path>,
    progress: &mut Progress,
    log: &mut Vec<RoundLog>,
) -> Result<(Vec<Row>, SceneSummary), BenchError> {
    let mut summary = SceneSummary {
        scene: spec.to_string(),
        size: None,
        images: String::new(),
        edge_pixels: None,
        reference_error: None,
        unique_surfaces: None,
        unique_surfaces_error: None,
    };
    let scene = match Scene::load_with(spec, &setup.assets).map(|s| s.lit(setup.lighting)) {
        Ok(scene) => {
            summary.size = Some(SceneSize::of(&scene));
            Arc::new(scene)
        }
        Err(source) => {
            let error = RowError::Scene {
                scene: spec.to_string(),
                source,
            };
            progress.note(format!("error: {error}"));
            // One row for the scene: no pipeline ran on it.
            return Ok((vec![Row::error(spec, "-", "", error.to_string())], summary));
        }
    };
    let images = out.map(|out| SceneImages::create(out, spec)).transpose()?;
    if let Some(images) = &images {
        summary.images = images.dir.display().to_string();
    }
    let run = SceneRun {
        setup,
        spec,
        host: host(
            scene,
            Overrides {
                shadows: setup.shadows,
                ..Overrides::default()
            },
        ),
        images,
    };
    let reference = match reference {
        Some(reference) => run.reference(reference, &mut summary, progress)?,
        None => None,
    };
    if out.is_some() {
        run.unique_surfaces(&mut summary, progress);
    }
    let rows = run.rows(pipelines, reference.as_ref(), &summary, progress, log)?;
    Ok((rows, summary))
}

/// Which of a pipeline's plans a timed plan is.
#[derive(Copy, Clone, PartialEq, Eq)]
enum Kind {
    Scene,
    General,
    PlanOnly,
}

/// A pipeline's timed plans after the rounds, each closed or the error that stopped it.
#[derive(Default)]
struct Outcomes {
    scene: Option<Result<Closed, FrameError>>,
    general: Option<Result<Closed, FrameError>>,
    plan_only: Option<Result<Closed, FrameError>>,
}

/// One loaded scene being measured.
struct SceneRun<'a> {
    setup: &'a Setup<'a>,
    spec: &'a str,
    host: Arc<Host>,
    /// `None` in sweeps.
    images: Option<SceneImages>,
}

impl SceneRun<'_> {
    /// The reference image and edge pixels; a reference that fails is noted in the
    /// summary and leaves the rows without error figures.
    fn reference(
        &self,
        reference: &Reference,
        summary: &mut SceneSummary,
        progress: &mut Progress,
    ) -> Result<Option<SceneReference>, BenchError> {
        progress.item(format!("{} reference", self.spec));
        let rendered = match reference.render(self.setup, &self.host) {
            Ok(rendered) => rendered,
            Err(e) => {
                progress.note(format!("error: reference on {}: {e}", self.spec));
                summary.reference_error = Some(e.to_string());
                return Ok(None);
            }
        };
        if let Some(images) = &self.images {
            images.write("reference", &rendered.image)?;
            let (w, h) = rendered.image.dimensions();
            images.write("edge_pixels", &rendered.edges.image(w, h))?;
        }
        summary.edge_pixels = Some(rendered.edges.clone());
        Ok(Some(rendered))
    }

    /// The lower bound of shading work, or why it could not be measured.
    fn unique_surfaces(&self, summary: &mut SceneSummary, progress: &mut Progress) {
        progress.item(format!("{} unique surfaces", self.spec));
        match surfaces::measure(self.setup, &self.host) {
            Ok(bound) => summary.unique_surfaces = Some(bound),
            Err(e) => {
                progress.note(format!("error: unique surfaces on {}: {e}", self.spec));
                summary.unique_surfaces_error = Some(e.to_string());
            }
        }
    }

    /// Every pipeline's row: its plans compiled, timed together in interleaved rounds,
    /// then each measured, compared and its images written; or an error row.
    fn rows(
        &self,
        pipelines: &[Candidate],
        reference: Option<&SceneReference>,
        summary: &SceneSummary,
        progress: &mut Progress,
        log: &mut Vec<RoundLog>,
    ) -> Result<Vec<Row>, BenchError> {
        let spec = self.spec;
        let mut plans = Vec::new();
        let mut outcomes: Vec<Result<About, FrameError>> = Vec::new();
        for (owner, candidate) in pipelines.iter().enumerate() {
            progress.item(format!("{spec} {}: compile", candidate.name));
            match self.setup.prepare(candidate, &self.host) {
                Ok(prepared) => {
                    let name = &candidate.name;
                    plans.push(timed(name.clone(), prepared.scene, (owner, Kind::Scene)));
                    if let Some(general) = prepared.general {
                        let name = format!("{name} (general)");
                        plans.push(timed(name, general, (owner, Kind::General)));
                    }
                    if let Some(plan_only) = prepared.plan_only {
                        let name = format!("{name} (plan only)");
                        plans.push(timed(name, plan_only, (owner, Kind::PlanOnly)));
                    }
                    outcomes.push(Ok(prepared.about));
                }
                Err(error) => outcomes.push(Err(error)),
            }
        }
        let mut timed: Vec<Outcomes> = pipelines.iter().map(|_| Outcomes::default()).collect();
        let closed = interleave(self.setup, spec, plans, progress, log, |plan, timing| {
            let (owner, kind) = plan.tag;
            let closed = timing.and_then(|t| Closed::of(&plan.prepared, t, kind == Kind::Scene));
            (owner, kind, closed)
        });
        for (owner, kind, closed) in closed {
            let slot = &mut timed[owner];
            match kind {
                Kind::Scene => slot.scene = Some(closed),
                Kind::General => slot.general = Some(closed),
                Kind::PlanOnly => slot.plan_only = Some(closed),
            }
        }
        pipelines
            .iter()
            .zip(outcomes)
            .zip(timed)
            .map(|((candidate, about), timed)| {
                progress.item(format!("{spec} {}", candidate.name));
                let measured = about.and_then(|about| {
                    // Every prepared pipeline's scene plan was timed.
                    let scene = timed.scene.expect("the scene's plan was timed")?;
                    let general = timed.general.transpose()?;
                    let plan_only = timed.plan_only.transpose()?;
                    self.setup
                        .finish(candidate, &self.host, about, scene, general, plan_only)
                });
                self.row(candidate, measured, reference, summary, progress)
            })
            .collect()
    }

    /// One pipeline's row: compared and its images written, or an error row.
    fn row(
        &self,
        candidate: &Candidate,
        measured: Result<Measured, FrameError>,
        reference: Option<&SceneReference>,
        summary: &SceneSummary,
        progress: &mut Progress,
    ) -> Result<Row, BenchError> {
        let (spec, name) = (self.spec, candidate.name.as_str());
        let file = candidate.path.display().to_string();
        match measured {
            Ok(measured) => {
                let mut figures = self.record(measured, name, &candidate.path, reference)?;
                // The bound holds for pipelines at the sample count it was counted at.
                figures.work.unique_surface_bound = summary
                    .unique_surfaces
                    .as_ref()
                    .filter(|b| b.samples == figures.samples)
                    .map(|b| b.per_pixel);
                Ok(Row::ok(spec, name, &file, figures))
            }
            Err(source) => {
                let error = RowError::Frame {
                    pipeline: name.to_string(),
                    scene: spec.to_string(),
                    source,
                };
                progress.note(format!("error: {error}"));
                Ok(Row::error(spec, name, &file, error.to_string()))
            }
        }
    }

    /// Compares a measured image with the reference and writes the pipeline's images and
    /// its plan's page.
    fn record(
        &self,
        measured: Measured,
        name: &str,
        file: &Path,
        reference: Option<&SceneReference>,
    ) -> Result<Figures, BenchError> {
        let Measured {
            mut figures,
            color,
            edges,
            plan,
            setting,
        } = measured;
        let heat = reference.map(|reference| {
            let (error, heat) = compare(&reference.image, &color, &reference.edges);
            figures.image_error = Some(error);
            heat
        });
        if let Some(images) = &self.images {
            images.write(name, &color)?;
            if let Some(edges) = &edges {
                images.write(&format!("{name}_edges"), edges)?;
            }
            if let Some(heat) = &heat {
                images.write(&format!("{name}_error"), heat)?;
            }
            let page = plan_page::html(self.setup, self.spec, name, file, &plan, setting, &figures);
            images.write_page(&plan_page::file_name(name), &page)?;
        }
        Ok(figures)
    }
}

fn timed<'s>(name: String, prepared: Prepared<'s>, tag: (usize, Kind)) -> Timed<'s, (usize, Kind)> {
    Timed {
        name,
        prepared,
        tag,
    }
}
