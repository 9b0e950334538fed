//! What a bench measures: the scenes and the pipelines, from the arguments or the defaults.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use rgraph_core::embedded;
use rgraph_core::file::{declared_params, load_file, GraphParams};
use rgraph_passes::Host;
use rgraph_scene::{builtin_names, BUILTIN_PREFIX};

use crate::cli::MSAA;
use crate::frame::{FrameError, Pipeline, Specialise};
use crate::registry::registry;

/// The directory the default pipelines come from.
pub const PIPELINE_DIR: &str = "pipelines";
/// The output every measured pipeline exports: its final image.
pub const COLOR: &str = "color";

/// A pipeline to measure: a file, or a variant of one made by rewriting its text.
#[derive(Clone, Debug)]
pub struct Candidate {
    /// The name rows and charts show: the file stem, plus the variant.
    pub name: String,
    pub path: PathBuf,
    /// The rewritten text of a variant; `None` to read the file.
    pub text: Option<String>,
    /// Values for the file's parameters.
    pub params: GraphParams,
}

impl Candidate {
    pub fn file(path: &Path) -> Candidate {
        Candidate {
            name: stem(path),
            path: path.to_path_buf(),
            text: None,
            params: GraphParams::new(),
        }
    }

    /// This pipeline at `samples` samples, when its file has the `msaa` parameter
    /// (`samples: Param(name: "msaa", default: 4)`); `None` when it has none, or cannot be
    /// read (loading it then reports why, in its row).
    pub fn at_samples(&self, samples: u32) -> Option<Candidate> {
        self.with_param(MSAA, samples)
    }

    /// This pipeline with its file's parameter `name` at `value`, named as before; `None`
    /// when the file does not declare it, or cannot be read.
    fn with_param(&self, name: &str, value: u32) -> Option<Candidate> {
        declared_params(&self.path, &registry()).ok()?.get(name)?;
        Some(Candidate {
            params: self.params.clone().with(name, value),
            ..self.clone()
        })
    }

    /// The file stem, without any variant suffix.
    pub fn stem(&self) -> String {
        stem(&self.path)
    }

    pub fn load(
        &self,
        host: Arc<Host>,
        outputs: &[&str],
        specialise: Specialise,
    ) -> Result<Pipeline, FrameError> {
        match &self.text {
            Some(text) => {
                Pipeline::from_text(&self.path, text, host, outputs, specialise, &self.params)
            }
            None => Pipeline::load(&self.path, host, outputs, specialise, &self.params),
        }
    }
}

/// `--scene` values, else every built-in scene.
pub fn scenes(asked: &[String]) -> Vec<String> {
    if !asked.is_empty() {
        return asked.to_vec();
    }
    builtin_names()
        .iter()
        .map(|b| format!("{BUILTIN_PREFIX}{}", b.name))
        .collect()
}

/// `--pipeline` values, else every file in `pipelines/` that exports "color", sorted; the
/// second list says which files were left out and why.
pub fn pipelines(asked: &[PathBuf]) -> (Vec<Candidate>, Vec<String>) {
    if !asked.is_empty() {
        return (
            asked.iter().map(|p| Candidate::file(p)).collect(),
            Vec::new(),
        );
    }
    let mut files: Vec<PathBuf> = match std::fs::read_dir(PIPELINE_DIR) {
        Ok(entries) => entries.filter_map(|e| Some(e.ok()?.path())).collect(),
        // Away from the repository: the pipelines built into the binary.
        Err(_) => embedded::list(PIPELINE_DIR)
            .into_iter()
            .map(PathBuf::from)
            .collect(),
    };
    files.retain(|p| p.extension().is_some_and(|e| e == "ron"));
    files.sort();
    let mut notes = Vec::new();
    let mut kept = Vec::new();
    for file in files {
        // Loading without a scene checks the outputs without a device; a file that fails
        // to load stays in the list and becomes an error row with the loader's message.
        let exports_color = load_file(&file, &registry())
            .map(|g| g.outputs().contains(&COLOR))
            .unwrap_or(true);
        if exports_color {
            kept.push(Candidate::file(&file));
        } else {
            notes.push(format!(
                "{} skipped: a generic demo, it exports no \"{COLOR}\" output",
                file.display()
            ));
        }
    }
    if kept.is_empty() {
        notes.push(format!(
            "no pipeline in {PIPELINE_DIR}/ (run from the repository root, or pass --pipeline)"
        ));
    }
    (kept, notes)
}

/// `pipelines` at `samples` samples (`--samples`), those whose files have the `msaa`
/// parameter; the others as they are, each named in a note.
pub fn at_samples(
    pipelines: Vec<Candidate>,
    samples: u32,
    notes: &mut Vec<String>,
) -> Vec<Candidate> {
    pipelines
        .into_iter()
        .map(|candidate| {
            candidate.at_samples(samples).unwrap_or_else(|| {
                notes.push(format!(
                    "--samples {samples}: {} has no \"{MSAA}\" parameter; measured as written",
                    candidate.path.display()
                ));
                candidate
            })
        })
        .collect()
}

/// `pipelines` with the `--param` values each file declares, named with them: a
/// candidate for each combination of the values given (one, unless a parameter has
/// several); a note for each parameter a file does not declare.
pub fn with_params(
    pipelines: Vec<Candidate>,
    given: &[(String, Vec<u32>)],
    notes: &mut Vec<String>,
) -> Vec<Candidate> {
    if given.is_empty() {
        return pipelines;
    }
    let mut expanded = Vec::new();
    for candidate in pipelines {
        let declared = declared_params(&candidate.path, &registry()).unwrap_or_default();
        // Each combination so far: the candidate's parameters and the names applied.
        let mut combinations = vec![(candidate.params.clone(), Vec::new())];
        for (name, values) in given {
            if declared.get(name).is_none() {
                notes.push(format!(
                    "--param {name}: {} has no \"{name}\" parameter",
                    candidate.path.display()
                ));
                continue;
            }
            combinations = (combinations.iter())
                .flat_map(|(params, applied): &(GraphParams, Vec<String>)| {
                    values.iter().map(move |value| {
                        let mut applied = applied.clone();
                        applied.push(format!("{name}={value}"));
                        (params.clone().with(name, *value), applied)
                    })
                })
                .collect();
        }
        for (params, applied) in combinations {
            let mut candidate = candidate.clone();
            candidate.params = params;
            if !applied.is_empty() {
                candidate.name = format!("{} [{}]", candidate.name, applied.join(", "));
            }
            expanded.push(candidate);
        }
    }
    expanded
}

/// The graph parameter that keeps a shadow atlas while nothing moves
/// (pipelines/parts/shadow_maps_compute.ron).
const SHADOW_CACHE: &str = "shadow_cache";

/// `pipelines` drawing their shadow maps every frame, unless `--param` gave
/// [`SHADOW_CACHE`]: the bench's frames are still, so a kept atlas would leave the maps'
/// cost out of every frame but the first, and out of the comparison with pipelines that
/// draw theirs each frame. A note names the files so measured.
pub fn drawing_shadow_maps(
    pipelines: Vec<Candidate>,
    given: &[(String, Vec<u32>)],
    notes: &mut Vec<String>,
) -> Vec<Candidate> {
    if given.iter().any(|(name, _)| name == SHADOW_CACHE) {
        return pipelines;
    }
    let mut files = Vec::new();
    let pipelines = (pipelines.into_iter())
        .map(|candidate| match candidate.with_param(SHADOW_CACHE, 0) {
            Some(drawing) => {
                let file = drawing.path.display().to_string();
                if !files.contains(&file) {
                    files.push(file);
                }
                drawing
            }
            None => candidate,
        })
        .collect();
    if !files.is_empty() {
        notes.push(format!(
            "shadow maps drawn every frame ({SHADOW_CACHE}=0 for {}): still frames would keep \
             the last frame's atlas; --param {SHADOW_CACHE}=0,1 measures both",
            files.join(", ")
        ));
    }
    pipelines
}

fn stem(path: &Path) -> String {
    path.file_stem().map_or_else(
        || path.display().to_string(),
        |s| s.to_string_lossy().into_owned(),
    )
}
