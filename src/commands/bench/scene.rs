//! One scene of a bench: its reference, edge pixels and unique-surface bound, then every
//! pipeline measured, compared with the reference, and its images written.

use std::path::Path;
use std::sync::Arc;

use passes_deferred_msaa::scene::Scene;
use passes_deferred_msaa::{Host, Overrides};

use super::candidates::Candidate;
use super::error::{BenchError, RowError};
use super::figures::Figures;
use super::image_error::compare;
use super::images::SceneImages;
use super::measure::{Measured, Setup};
use super::progress::Progress;
use super::reference::{Reference, SceneReference};
use super::results::{Row, SceneSummary};
use super::surfaces;
use crate::frame::host;

/// Every pipeline on the scene `spec`. When `out` is given (outside sweeps), also the
/// images under it and the unique-surface bound. A scene that fails to load is one error
/// row; a pipeline that fails is an error row and the others go on. Only writing images
/// fails the whole bench.
pub fn bench_scene(
    setup: &Setup,
    spec: &str,
    pipelines: &[Candidate],
    reference: Option<&Reference>,
    out: Option<&Path>,
    progress: &mut Progress,
) -> Result<(Vec<Row>, SceneSummary), BenchError> {
    let mut summary = SceneSummary {
        scene: spec.to_string(),
        images: String::new(),
        edge_pixels: None,
        reference_error: None,
        unique_surfaces: None,
        unique_surfaces_error: None,
    };
    let scene = match Scene::load_with(spec, &setup.assets).map(|s| s.lit(setup.lighting)) {
        Ok(scene) => Arc::new(scene),
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
        host: host(scene, Overrides::default()),
        images,
    };
    let reference = match reference {
        Some(reference) => run.reference(reference, &mut summary, progress)?,
        None => None,
    };
    if out.is_some() {
        run.unique_surfaces(&mut summary, progress);
    }
    let rows = pipelines
        .iter()
        .map(|candidate| run.row(candidate, reference.as_ref(), &summary, progress))
        .collect::<Result<_, _>>()?;
    Ok((rows, summary))
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

    /// One pipeline's row: measured, compared and its images written, or an error row.
    fn row(
        &self,
        candidate: &Candidate,
        reference: Option<&SceneReference>,
        summary: &SceneSummary,
        progress: &mut Progress,
    ) -> Result<Row, BenchError> {
        let (spec, name) = (self.spec, candidate.name.as_str());
        progress.item(format!("{spec} {name}"));
        let file = candidate.path.display().to_string();
        match self.setup.measure(candidate, &self.host) {
            Ok(measured) => {
                let mut figures = self.record(measured, name, reference)?;
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

    /// Compares a measured image with the reference and writes the pipeline's images.
    fn record(
        &self,
        measured: Measured,
        name: &str,
        reference: Option<&SceneReference>,
    ) -> Result<Figures, BenchError> {
        let Measured {
            mut figures,
            color,
            edges,
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
        }
        Ok(figures)
    }
}
