//! `--sweep`: the same measurement at several values of one parameter, to see how cost
//! grows. Each value is a [`Step`]: the scenes, pipelines and size measured together.
//!
//! - triangles: builtin:terrain?cells=N, one mesh of 2 N^2 triangles, one step a decade
//!   from 10^4 to 10^8 (replaces --scene);
//! - meshes: builtin:city?blocks=K, K^2 buildings of 12 triangles each its own mesh, and
//!   the ground: 2 to about 10^5 meshes (replaces --scene);
//! - lights: builtin:lights?count=N, N = 1, 4, 16, ..., 65,536 (replaces --scene);
//! - resolution: 1280x720, 1920x1080, 2560x1440, 3840x2160 (replaces --width/--height);
//! - samples: each pipeline whose file has the `msaa` parameter
//!   (`samples: Param(name: "msaa", default: 4)`) at 1, 2, 4 and 8; the others as
//!   written. A count the device lacks fails that variant's compile, which becomes an
//!   error row; so does a pipeline whose passes need multisampled inputs at 1 sample.
//!
//! `--sweep-max` drops the values above it. Sweeps measure time, memory and work only: no
//! reference, no image error, no images.

use clap::ValueEnum;
use serde::Serialize;

use super::candidates::Candidate;
use crate::cli::Sweep;

/// Where a row sits in a sweep.
#[derive(Clone, Debug, Serialize)]
pub struct SweepPoint {
    pub parameter: Sweep,
    /// Triangle, mesh or light count, image height, or sample count.
    pub value: u32,
    /// The value as a person reads it: "100,352 triangles", "1920x1080", "8x".
    pub label: String,
}

/// What one step measures.
pub struct Step {
    pub point: Option<SweepPoint>,
    pub scenes: Vec<String>,
    pub pipelines: Vec<Candidate>,
    pub size: (u32, u32),
}

/// Terrain cells per side whose 2 N^2 triangles come nearest each decade, 10^4 to 10^8.
const TERRAIN_CELLS: [u32; 5] = [71, 224, 707, 2236, 7071];
/// City blocks per side: K^2 buildings and the ground, 2 to 99,857 meshes.
const CITY_BLOCKS: [u32; 6] = [1, 3, 10, 32, 100, 316];
const LIGHTS: [u32; 9] = [1, 4, 16, 64, 256, 1024, 4096, 16384, 65536];
const RESOLUTIONS: [(u32, u32); 4] = [(1280, 720), (1920, 1080), (2560, 1440), (3840, 2160)];
const SAMPLES: [u32; 4] = [1, 2, 4, 8];

/// One step without a sweep; one per value (at most `max`) with one.
pub fn steps(
    sweep: Option<Sweep>,
    max: Option<u32>,
    scenes: Vec<String>,
    pipelines: Vec<Candidate>,
    size: (u32, u32),
    notes: &mut Vec<String>,
) -> Vec<Step> {
    let Some(sweep) = sweep else {
        return vec![Step {
            point: None,
            scenes,
            pipelines,
            size,
        }];
    };
    let step = |value: u32, label: String| Step {
        point: Some(SweepPoint {
            parameter: sweep,
            value,
            label,
        }),
        scenes: scenes.clone(),
        pipelines: pipelines.clone(),
        size,
    };
    // A sweep over a built-in scene's parameter: the scene `spec` at each (value, label).
    let mut scene_sweep = |spec: &str, points: Vec<(u32, String, String)>| {
        let name = sweep.to_possible_value().map(|v| v.get_name().to_owned());
        notes.push(format!(
            "{} sweep: the scene is {spec} (any --scene is replaced)",
            name.unwrap_or_default()
        ));
        points
            .into_iter()
            .map(|(value, query, label)| Step {
                scenes: vec![format!("{spec}?{query}")],
                ..step(value, label)
            })
            .collect::<Vec<_>>()
    };
    let steps = match sweep {
        Sweep::Triangles => scene_sweep(
            "builtin:terrain",
            TERRAIN_CELLS
                .iter()
                .map(|&n| {
                    let triangles = 2 * n * n;
                    (
                        triangles,
                        format!("cells={n}"),
                        format!("{} triangles", grouped(triangles)),
                    )
                })
                .collect(),
        ),
        Sweep::Meshes => scene_sweep(
            "builtin:city",
            CITY_BLOCKS
                .iter()
                .map(|&k| {
                    let meshes = k * k + 1;
                    (
                        meshes,
                        format!("blocks={k}"),
                        format!("{} meshes", grouped(meshes)),
                    )
                })
                .collect(),
        ),
        Sweep::Lights => scene_sweep(
            "builtin:lights",
            LIGHTS
                .iter()
                .map(|&n| (n, format!("count={n}"), format!("{} lights", grouped(n))))
                .collect(),
        ),
        Sweep::Resolution => RESOLUTIONS
            .iter()
            .map(|&(w, h)| Step {
                size: (w, h),
                ..step(h, format!("{w}x{h}"))
            })
            .collect(),
        Sweep::Samples => SAMPLES
            .iter()
            .map(|&n| Step {
                pipelines: pipelines.iter().map(|c| with_samples(c, n)).collect(),
                ..step(n, format!("{n}x"))
            })
            .collect(),
    };
    let max = max.unwrap_or(u32::MAX);
    steps
        .into_iter()
        .filter(|s| s.point.as_ref().is_some_and(|p| p.value <= max))
        .collect()
}

/// `n` with thousands separated by commas: 99998082 -> "99,998,082".
fn grouped(n: u32) -> String {
    let digits = n.to_string();
    let mut out = String::new();
    for (i, digit) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i).is_multiple_of(3) {
            out.push(',');
        }
        out.push(digit);
    }
    out
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
        let mut sweep = |sweep, max| steps(Some(sweep), max, vec![], vec![], (64, 48), &mut notes);
        let lights = sweep(Sweep::Lights, None);
        assert_eq!(lights.len(), 9);
        assert_eq!(lights[3].scenes, ["builtin:lights?count=64"]);
        assert_eq!(lights[8].point.as_ref().unwrap().label, "65,536 lights");
        let triangles = sweep(Sweep::Triangles, None);
        let counts: Vec<u32> = triangles
            .iter()
            .map(|s| s.point.as_ref().unwrap().value)
            .collect();
        assert_eq!(counts, [10_082, 100_352, 999_698, 9_999_392, 99_998_082]);
        assert_eq!(triangles[4].scenes, ["builtin:terrain?cells=7071"]);
        assert_eq!(
            triangles[4].point.as_ref().unwrap().label,
            "99,998,082 triangles"
        );
        let meshes = sweep(Sweep::Meshes, Some(10_001));
        assert_eq!(meshes.len(), 5, "the 99,857-mesh step is past --sweep-max");
        assert_eq!(meshes[4].scenes, ["builtin:city?blocks=100"]);
        let sizes = sweep(Sweep::Resolution, None);
        assert_eq!(sizes.last().map(|s| s.size), Some((3840, 2160)));
        assert_eq!(
            steps(None, None, vec![], vec![], (64, 48), &mut notes).len(),
            1
        );
    }
}
