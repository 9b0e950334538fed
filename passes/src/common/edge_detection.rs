//! How edge pixels are found: the detectors and thresholds `edge_stencil` (which marks
//! edge pixels in the stencil for the fragment light passes) and `light_tiled` (which
//! classifies pixels in compute) share, with one WGSL definition (edge_detect.wgsl), so
//! both paths call the same pixels edges.
//!
//! ```ron
//! (detector: compare,   // the default; or centroid | coverage | all | none
//!  depth_threshold: 0.01, normal_threshold: 0.95, albedo_threshold: 0.05)
//! ```
//!
//! - `compare`: some sample differs from sample 0 in view depth by more than
//!   `depth_threshold` times the larger depth, in normal by a cosine below
//!   `normal_threshold`, in an albedo channel by more than `albedo_threshold`, or in its
//!   material flags (lit, unlit, background);
//! - `centroid`: some sample's fragment had its centroid away from the pixel center
//!   (seed 000's centroid trick, recorded by the G-buffer pass; an implementation may
//!   put the centroid at the center whenever that is covered, so it can miss edges;
//!   whether it sees intersection edges is the implementation's too: lavapipe takes the
//!   centroid from the coverage left after its early depth test and marks them,
//!   tests/deferred_detectors.rs);
//! - `coverage`: some sample's fragment covered only part of the pixel
//!   (`@builtin(sample_mask)` as a G-buffer input; misses intersection edges, where both
//!   surfaces cover every sample);
//! - `all`: every pixel, i.e. per-sample shading everywhere; `none`: no pixel.

use serde::Deserialize;

use rgraph_core::file::PluginError;

#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EdgeDetection {
    #[serde(default)]
    pub detector: Detector,
    #[serde(default = "depth_threshold")]
    pub depth_threshold: f32,
    #[serde(default = "normal_threshold")]
    pub normal_threshold: f32,
    #[serde(default = "albedo_threshold")]
    pub albedo_threshold: f32,
}

impl Default for EdgeDetection {
    fn default() -> Self {
        EdgeDetection {
            detector: Detector::default(),
            depth_threshold: depth_threshold(),
            normal_threshold: normal_threshold(),
            albedo_threshold: albedo_threshold(),
        }
    }
}

fn depth_threshold() -> f32 {
    0.01
}
fn normal_threshold() -> f32 {
    0.95
}
fn albedo_threshold() -> f32 {
    0.05
}

#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Detector {
    #[default]
    Compare,
    Centroid,
    Coverage,
    All,
    None,
}

/// `EDGE_CENTROID` and `EDGE_COVERAGE` in common.wgsl.
const EDGE_CENTROID: f64 = 128.0;
const EDGE_COVERAGE: f64 = 64.0;

impl EdgeDetection {
    /// Thresholds in their ranges: an error naming the parameter otherwise.
    pub(crate) fn check(&self) -> Result<(), PluginError> {
        let bad = |name: &str, value: f32, range: &str| {
            PluginError::Invalid(format!("{name} must be {range}, got {value}"))
        };
        if !(self.depth_threshold.is_finite() && self.depth_threshold >= 0.0) {
            return Err(bad(
                "depth_threshold",
                self.depth_threshold,
                "finite and >= 0",
            ));
        }
        if !(-1.0..=1.0).contains(&self.normal_threshold) {
            return Err(bad(
                "normal_threshold",
                self.normal_threshold,
                "a cosine in [-1, 1]",
            ));
        }
        if !(self.albedo_threshold.is_finite() && self.albedo_threshold >= 0.0) {
            return Err(bad(
                "albedo_threshold",
                self.albedo_threshold,
                "finite and >= 0",
            ));
        }
        Ok(())
    }

    /// The G-buffer slots the detector reads.
    pub(crate) fn reads(&self) -> &'static [&'static str] {
        match self.detector {
            Detector::Compare => &["albedo", "normal", "material", "view_depth"],
            Detector::Centroid | Detector::Coverage => &["material"],
            Detector::All | Detector::None => &[],
        }
    }

    /// edge_detect.wgsl's pipeline constants.
    pub(crate) fn constants(&self) -> Vec<(&'static str, f64)> {
        let edge_bit = match self.detector {
            Detector::Coverage => EDGE_COVERAGE,
            Detector::Compare | Detector::Centroid | Detector::All | Detector::None => {
                EDGE_CENTROID
            }
        };
        vec![
            ("DEPTH_THRESHOLD", f64::from(self.depth_threshold)),
            ("NORMAL_THRESHOLD", f64::from(self.normal_threshold)),
            ("ALBEDO_THRESHOLD", f64::from(self.albedo_threshold)),
            ("EDGE_BIT", edge_bit),
        ]
    }
}
