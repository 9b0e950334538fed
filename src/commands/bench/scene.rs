//! One scene of a bench: its reference and edge pixels, then every pipeline measured,
//! compared with the reference, and its images written.

use std::path::Path;
use std::sync::Arc;

use passes_deferred_msaa::scene::Scene;
use passes_deferred_msaa::Overrides;
use serde::Serialize;

use super::candidates::Candidate;
use super::edge_pixels::EdgePixels;
use super::error::{BenchError, RowError};
use super::image_error::compare;
use super::images::SceneImages;
use super::measure::{Measured, Setup};
use super::progress::Progress;
use super::reference::{Reference, SceneReference};
use super::results::{Figures, Row};
use super::surfaces::{self, UniqueSurfaces};
use crate::frame::host;

/// What a scene's rows share: where its images are and how its edge pixels were found.
#[derive(Debug, Serialize)]
pub struct SceneSummary {
    pub scene: String,
    pub images: String,
    /// The pixels edge errors are measured on; `null` without a reference.
    pub edge_pixels: Option<EdgePixels>,
    /// Why the reference could not be rendered, when it could not.
    pub reference_error: Option<String>,
    /// The lower bound of shading work; `null` in sweeps or when it failed.
    pub unique_surfaces: Option<UniqueSurfaces>,
    /// Why the bound could not be measured, when it could not.
    pub unique_surfaces_error: Option<String>,
}

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
    let images = out.map(|out| SceneImages::create(out, spec)).transpose()?;
    let mut summary = SceneSummary {
        scene: spec.to_string(),
        images: images
            .as_ref()
            .map_or(String::new(), |i| i.dir.display().to_string()),
        edge_pixels: None,
        reference_error: None,
        unique_surfaces: None,
        unique_surfaces_error: None,
    };
    let scene = match Scene::load(spec) {
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
    let host = host(scene, Overrides::default());

    if reference.is_some() {
        progress.item(format!("{spec} reference"));
    }
    let reference = match reference.map(|r| r.render(setup, &host)) {
        Some(Ok(reference)) => {
            if let Some(images) = &images {
                images.write("reference", &reference.image)?;
                let (w, h) = reference.image.dimensions();
                images.write("edge_pixels", &reference.edges.image(w, h))?;
            }
            summary.edge_pixels = Some(reference.edges.clone());
            Some(reference)
        }
        Some(Err(e)) => {
            progress.note(format!("error: reference on {spec}: {e}"));
            summary.reference_error = Some(e.to_string());
            None
        }
        None => None,
    };

    if out.is_some() {
        progress.item(format!("{spec} unique surfaces"));
        match surfaces::measure(setup, &host) {
            Ok(bound) => summary.unique_surfaces = Some(bound),
            Err(e) => {
                progress.note(format!("error: unique surfaces on {spec}: {e}"));
                summary.unique_surfaces_error = Some(e.to_string());
            }
        }
    }

    let mut rows = Vec::new();
    for candidate in pipelines {
        progress.item(format!("{spec} {}", candidate.name));
        let file = candidate.path.display().to_string();
        let row = match setup.measure(candidate, &host) {
            Ok(measured) => {
                let mut figures = record(
                    measured,
                    &candidate.name,
                    reference.as_ref(),
                    images.as_ref(),
                )?;
                // The bound holds for pipelines at the sample count it was counted at.
                let bound = summary.unique_surfaces.as_ref();
                figures.work.unique_surface_bound = bound
                    .filter(|b| b.samples == figures.samples)
                    .map(|b| b.per_pixel);
                Row::ok(spec, &candidate.name, &file, figures)
            }
            Err(source) => {
                let error = RowError::Frame {
                    pipeline: candidate.name.clone(),
                    scene: spec.to_string(),
                    source,
                };
                progress.note(format!("error: {error}"));
                Row::error(spec, &candidate.name, &file, error.to_string())
            }
        };
        rows.push(row);
    }
    Ok((rows, summary))
}

/// Compares a measured image with the reference and writes the pipeline's images.
fn record(
    measured: Measured,
    name: &str,
    reference: Option<&SceneReference>,
    images: Option<&SceneImages>,
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
    if let Some(images) = images {
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
