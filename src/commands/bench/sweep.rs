//! `--sweep`: the same measurement at several values of one parameter, to see how cost
//! grows. Each value is a [`Step`]: the scenes, pipelines and size measured together.
//!
//! - lights: builtin:lights?count=N, N = 1, 4, 16, 64, 256, 1024 (replaces --scene);
//! - resolution: 1280x720, 1920x1080, 2560x1440, 3840x2160 (replaces --width/--height);
//! - samples: each pipeline whose file has the `msaa` parameter
//!   (`samples: Param(name: "msaa", default: 4)`) at 1, 2, 4 and 8; the others as
//!   written. A count the device lacks fails that variant's compile, which becomes an
//!   error row; so does a pipeline whose passes need multisampled inputs at 1 sample.
//!
//! Sweeps measure time and work only: no reference, no image error, no images.

use serde::Serialize;

use super::candidates::Candidate;
use crate::cli::Sweep;

/// Where a row sits in a sweep.
#[derive(Clone, Debug, Serialize)]
pub struct SweepPoint {
    pub parameter: Sweep,
    /// Light count, image height, or sample count.
    pub value: u32,
    /// The value as a person reads it: "64 lights", "1920x1080", "8x".
    pub label: String,
}

/// What one step measures.
pub struct Step {
    pub point: Option<SweepPoint>,
    pub scenes: Vec<String>,
    pub pipelines: Vec<Candidate>,
    pub size: (u32, u32),
}

const LIGHTS: [u32; 6] = [1, 4, 16, 64, 256, 1024];
const RESOLUTIONS: [(u32, u32); 4] = [(1280, 720), (1920, 1080), (2560, 1440), (3840, 2160)];
const SAMPLES: [u32; 4] = [1, 2, 4, 8];

/// The scene whose light count the lights sweep varies.
const LIGHTS_SCENE: &str = "builtin:lights";

/// One step without a sweep; one per value with one.
pub fn steps(
    sweep: Option<Sweep>,
    scenes: Vec<String>,
    pipelines: Vec<Candidate>,
    size: (u32, u32),
    notes: &mut Vec<String>,
) -> Vec<Step> {
    let point = |parameter, value, label| {
        Some(SweepPoint {
            parameter,
            value,
            label,
        })
    };
    match sweep {
        None => vec![Step {
            point: None,
            scenes,
            pipelines,
            size,
        }],
        Some(Sweep::Lights) => {
            notes.push(format!(
                "lights sweep: the scene is {LIGHTS_SCENE}?count=N (any --scene is replaced)"
            ));
            LIGHTS
                .iter()
                .map(|&n| Step {
                    point: point(Sweep::Lights, n, format!("{n} lights")),
                    scenes: vec![format!("{LIGHTS_SCENE}?count={n}")],
                    pipelines: pipelines.clone(),
                    size,
                })
                .collect()
        }
        Some(Sweep::Resolution) => RESOLUTIONS
            .iter()
            .map(|&(w, h)| Step {
                point: point(Sweep::Resolution, h, format!("{w}x{h}")),
                scenes: scenes.clone(),
                pipelines: pipelines.clone(),
                size: (w, h),
            })
            .collect(),
        Some(Sweep::Samples) => SAMPLES
            .iter()
            .map(|&n| Step {
                point: point(Sweep::Samples, n, format!("{n}x")),
                scenes: scenes.clone(),
                pipelines: pipelines.iter().map(|c| with_samples(c, n)).collect(),
                size,
            })
            .collect(),
    }
}

/// `candidate` at `samples` samples, or as it is when its file has no `msaa` parameter.
fn with_samples(candidate: &Candidate, samples: u32) -> Candidate {
    candidate
        .at_samples(samples)
        .unwrap_or_else(|| candidate.clone())
}

#[cfg(test)]
mod tests {
    use super::steps;
    use crate::cli::Sweep;

    #[test]
    fn each_sweep_value_is_a_step() {
        let mut notes = Vec::new();
        let lights = steps(Some(Sweep::Lights), vec![], vec![], (64, 48), &mut notes);
        assert_eq!(lights.len(), 6);
        assert_eq!(lights[3].scenes, ["builtin:lights?count=64"]);
        let sizes = steps(
            Some(Sweep::Resolution),
            vec![],
            vec![],
            (64, 48),
            &mut notes,
        );
        assert_eq!(sizes.last().map(|s| s.size), Some((3840, 2160)));
        assert_eq!(steps(None, vec![], vec![], (64, 48), &mut notes).len(), 1);
    }
}
