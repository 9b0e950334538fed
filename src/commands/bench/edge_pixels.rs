//! The pixels where anti-aliasing matters, one set per scene so every pipeline's edge
//! error is measured on the same pixels.
//!
//! Definition: a pixel is an edge pixel when the supersampled reference and a 1-sample
//! render of the same scene (deferred_noaa: every pixel shaded once at its center) differ
//! by more than [`THRESHOLD`] in any sRGB channel. Those are the pixels one sample per
//! pixel gets wrong: geometric edges, intersections and sub-pixel detail, which is what
//! MSAA exists for. The mask does not depend on the pipeline being measured (a pipeline's
//! own debug.edges would reward a detector for missing edges), and it needs no per-sample
//! primitive identity, which no pipeline exports. Smooth shading differs between a pixel's
//! center and its 16-sample average by far less than the threshold.

use image::{Rgba, RgbaImage};
use serde::Serialize;

/// 8 of 255 in any sRGB channel (about 3%).
pub const THRESHOLD: u8 = 8;

#[derive(Clone, Debug, Serialize)]
pub struct EdgePixels {
    /// Row by row, top row first; all false when no 1-sample render was available.
    #[serde(skip)]
    pub mask: Vec<bool>,
    /// The mask's pixels over all pixels.
    pub share: f64,
    /// How the mask was made.
    pub definition: String,
}

impl EdgePixels {
    /// Pixels where `reference` and the 1-sample render `aliased` differ by more than
    /// [`THRESHOLD`]; `aliased_name` names the render in the definition.
    pub fn between(reference: &RgbaImage, aliased: &RgbaImage, aliased_name: &str) -> EdgePixels {
        let mask: Vec<bool> = reference
            .pixels()
            .zip(aliased.pixels())
            .map(|(r, a)| (0..3).any(|c| r.0[c].abs_diff(a.0[c]) > THRESHOLD))
            .collect();
        let share = mask.iter().filter(|e| **e).count() as f64 / mask.len().max(1) as f64;
        EdgePixels {
            mask,
            share,
            definition: format!(
                "pixels where the reference and {aliased_name} (1 sample per pixel) differ by \
                 more than {THRESHOLD}/255 in any sRGB channel"
            ),
        }
    }

    /// No 1-sample render: edge figures are not measured.
    pub fn none(pixels: usize, why: String) -> EdgePixels {
        EdgePixels {
            mask: vec![false; pixels],
            share: 0.0,
            definition: why,
        }
    }

    /// White on black, for a person to see where the edge error is measured.
    pub fn image(&self, width: u32, height: u32) -> RgbaImage {
        RgbaImage::from_fn(width, height, |x, y| {
            let edge = self.mask.get((y * width + x) as usize) == Some(&true);
            let v = if edge { 255 } else { 0 };
            Rgba([v, v, v, 255])
        })
    }
}
