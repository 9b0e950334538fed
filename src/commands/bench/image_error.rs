//! Error of a pipeline's image against the reference: mean FLIP (NVIDIA's perceptual
//! metric, on the tone-mapped 8-bit sRGB images, as FLIP's LDR mode expects) and PSNR,
//! over all pixels and over the scene's edge pixels.

use image::{Rgba, RgbaImage};
use serde::Serialize;

use super::edge_pixels::EdgePixels;

#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ImageError {
    pub flip_mean: f64,
    /// Mean squared error of the sRGB channels (0..255), all pixels.
    pub mse: f64,
    /// 10 log10(255² / mse); `null` when the images are identical (infinite PSNR).
    pub psnr_db: Option<f64>,
    /// The same three restricted to the scene's edge pixels; `null` when it has none.
    pub edge_flip_mean: Option<f64>,
    pub edge_mse: Option<f64>,
    pub edge_psnr_db: Option<f64>,
}

/// The figures and FLIP's error map as a heat map (magma: black is no error).
pub fn compare(
    reference: &RgbaImage,
    test: &RgbaImage,
    edges: &EdgePixels,
) -> (ImageError, RgbaImage) {
    let (width, height) = reference.dimensions();
    let flip_map = nv_flip::flip(
        rgb(reference),
        rgb(test),
        nv_flip::DEFAULT_PIXELS_PER_DEGREE,
    );
    let flip = flip_map.to_vec();
    let squared: Vec<f64> = reference
        .pixels()
        .zip(test.pixels())
        .map(|(r, t)| {
            (0..3)
                .map(|c| (r.0[c] as f64 - t.0[c] as f64).powi(2))
                .sum::<f64>()
                / 3.0
        })
        .collect();
    let all = |_: usize| true;
    let on_edge = |i: usize| edges.mask[i];
    let mse = mean(&squared, all).unwrap_or(0.0);
    let edge_mse = mean(&squared, on_edge);
    let error = ImageError {
        flip_mean: mean(&flip, all).unwrap_or(0.0),
        mse,
        psnr_db: psnr(mse),
        edge_flip_mean: mean(&flip, on_edge),
        edge_mse,
        edge_psnr_db: edge_mse.and_then(psnr),
    };
    let heat = flip_map.apply_color_lut(&nv_flip::magma_lut()).to_vec();
    let heat = RgbaImage::from_fn(width, height, |x, y| {
        let i = 3 * (y * width + x) as usize;
        Rgba([heat[i], heat[i + 1], heat[i + 2], 255])
    });
    (error, heat)
}

/// Mean FLIP of `test` against `reference` over all pixels (images of one size).
pub fn flip_mean(reference: &RgbaImage, test: &RgbaImage) -> f64 {
    let flip_map = nv_flip::flip(
        rgb(reference),
        rgb(test),
        nv_flip::DEFAULT_PIXELS_PER_DEGREE,
    );
    mean(&flip_map.to_vec(), |_| true).unwrap_or(0.0)
}

fn rgb(image: &RgbaImage) -> nv_flip::FlipImageRgb8 {
    let bytes: Vec<u8> = image
        .pixels()
        .flat_map(|p| [p.0[0], p.0[1], p.0[2]])
        .collect();
    nv_flip::FlipImageRgb8::with_data(image.width(), image.height(), &bytes)
}

/// The mean of the values whose index `keep` accepts; `None` when it accepts none.
fn mean<T: Copy + Into<f64>>(values: &[T], keep: impl Fn(usize) -> bool) -> Option<f64> {
    let (sum, n) = values
        .iter()
        .enumerate()
        .filter(|(i, _)| keep(*i))
        .fold((0.0, 0usize), |(s, n), (_, v)| (s + (*v).into(), n + 1));
    (n > 0).then(|| sum / n as f64)
}

fn psnr(mse: f64) -> Option<f64> {
    (mse > 0.0).then(|| 10.0 * (255.0f64 * 255.0 / mse).log10())
}
