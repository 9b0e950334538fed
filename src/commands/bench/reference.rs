//! The reference images errors are measured against, and the 1-sample render that,
//! compared with it, finds each scene's edge pixels.

use std::path::Path;
use std::sync::Arc;

use rgraph_core::bounded_read::MAX_GRAPH_FILE_BYTES;
use rgraph_core::embedded;

use image::RgbaImage;
use rgraph_passes::Host;
use serde::Serialize;

use super::candidates::{Candidate, COLOR, PIPELINE_DIR};
use super::edge_pixels::EdgePixels;
use super::measure::Setup;
use crate::cli::BenchArgs;
use crate::frame::FrameError;

/// The built-in reference, whose shaded samples per pixel `--reference-spp` sets.
const BUILTIN: &str = "reference_ssaa16";
/// Used when the reference file is missing: every sample of 4x MSAA shaded.
const FALLBACK: &str = "deferred_per_sample_4x";
/// The 1-sample render the edge pixels are found with.
const ALIASED: &str = "deferred_noaa";

/// The reference pipeline of a run, and what the reader should know about it.
#[derive(Clone, Debug, Serialize)]
pub struct Reference {
    pub pipeline: String,
    pub file: String,
    /// Shaded samples per pixel, where known: the built-in reference's (`--reference-spp`)
    /// or the fallback's; `None` for another `--reference` file, which renders as written.
    pub spp: Option<u32>,
    #[serde(skip)]
    candidate: Candidate,
    #[serde(skip)]
    aliased: Candidate,
}

/// One scene's reference image and edge pixels.
pub struct SceneReference {
    pub image: RgbaImage,
    pub edges: EdgePixels,
}

impl Reference {
    /// `--reference` at `--reference-spp`, else the best available with a note saying
    /// so; `None` (with a note) when there is nothing to compare against.
    pub fn choose(args: &BenchArgs, notes: &mut Vec<String>) -> Option<Reference> {
        let aliased = Candidate::file(&Path::new(PIPELINE_DIR).join(format!("{ALIASED}.ron")));
        if embedded::exists(&args.reference) {
            let mut candidate = Candidate::file(&args.reference);
            if args.reference_spp == 4 {
                // The file shades 4 samples of a target twice the output's size; at the
                // output's size it shades 4 per pixel and the blit copies 1:1.
                let text = match embedded::read_text(&args.reference, MAX_GRAPH_FILE_BYTES) {
                    Ok(text) => text,
                    Err(e) => {
                        let file = args.reference.display();
                        notes.push(format!("{file}: {e}: image error is not measured"));
                        return None;
                    }
                };
                candidate.text = Some(text.replace("Relative(2.0)", "Relative(1.0)"));
                candidate.name = format!("{}@4spp", candidate.name);
            }
            let builtin = args.reference.file_stem().is_some_and(|s| s == BUILTIN);
            return Some(Reference {
                pipeline: candidate.name.clone(),
                file: args.reference.display().to_string(),
                spp: builtin.then_some(args.reference_spp),
                candidate,
                aliased,
            });
        }
        let fallback = Path::new(PIPELINE_DIR).join(format!("{FALLBACK}.ron"));
        if embedded::exists(&fallback) {
            notes.push(format!(
                "{} is missing: the reference is {FALLBACK} (4 shaded samples per pixel), \
                 the best pipeline available",
                args.reference.display()
            ));
            return Some(Reference {
                pipeline: FALLBACK.into(),
                file: fallback.display().to_string(),
                spp: Some(4),
                candidate: Candidate::file(&fallback),
                aliased,
            });
        }
        notes.push(format!(
            "{} and {} are missing: image error is not measured",
            args.reference.display(),
            fallback.display()
        ));
        None
    }

    /// Renders the reference and the 1-sample image on the scene of `host`.
    pub fn render(&self, setup: &Setup, host: &Arc<Host>) -> Result<SceneReference, FrameError> {
        let image = setup.render(&self.candidate, host, COLOR)?;
        let pixels = image.width() as usize * image.height() as usize;
        let edges = match setup.render(&self.aliased, host, COLOR) {
            Ok(aliased) => EdgePixels::between(&image, &aliased, ALIASED),
            Err(e) => EdgePixels::none(pixels, format!("not measured: {e}")),
        };
        Ok(SceneReference { image, edges })
    }
}
