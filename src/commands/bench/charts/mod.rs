//! The charts a bench writes, drawn with plotters into memory and saved through the same
//! PNG writer as the images. Text uses the DejaVu Sans file committed under assets/fonts,
//! registered with plotters' ab_glyph backend, so no system font is needed.

mod pareto;
mod passes;
mod scaling;

use std::path::Path;
use std::sync::Once;

use image::{Rgba, RgbaImage};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::{register_font, FontStyle};

use super::error::BenchError;
use super::results::Results;
use crate::commands::write_png;

use pareto::pareto;
use passes::passes;
use scaling::scaling;

static FONT: &[u8] = include_bytes!("../../../../assets/fonts/DejaVuSans.ttf");

/// The family every chart's text names.
const FAMILY: &str = "sans-serif";

/// A drawing area on an in-memory RGB bitmap.
pub type Area<'a> = DrawingArea<BitMapBackend<'a>, Shift>;

/// Any drawing error, as text: plotters' errors are generic over the backend.
pub type DrawResult = Result<(), String>;

/// Writes the charts of `results` into `out`: pareto.png and passes.png, or scaling.png
/// for a sweep.
pub fn write_all(results: &Results, out: &Path) -> Result<(), BenchError> {
    if let Some(sweep) = results.sweep {
        return draw_png(&out.join("scaling.png"), scaling::size(results), |area| {
            scaling(results, sweep, area)
        });
    }
    draw_png(&out.join("pareto.png"), pareto::size(results), |area| {
        pareto(results, area)
    })?;
    draw_png(&out.join("passes.png"), passes::size(results), |area| {
        passes(results, area)
    })
}

/// Draws `size` pixels with `draw` on a white background and writes them as a PNG.
pub fn draw_png(
    path: &Path,
    size: (u32, u32),
    draw: impl FnOnce(&Area) -> DrawResult,
) -> Result<(), BenchError> {
    static REGISTER: Once = Once::new();
    REGISTER.call_once(|| {
        // The font is compiled in: it parses, or no chart could ever have been drawn.
        let _ = register_font(FAMILY, FontStyle::Normal, FONT);
    });
    let failed = |reason: String| BenchError::Write {
        path: path.to_path_buf(),
        reason,
    };
    let mut rgb = vec![0u8; size.0 as usize * size.1 as usize * 3];
    {
        let area = BitMapBackend::with_buffer(&mut rgb, size).into_drawing_area();
        area.fill(&WHITE).map_err(|e| failed(e.to_string()))?;
        draw(&area).map_err(failed)?;
        area.present().map_err(|e| failed(e.to_string()))?;
    }
    let image = RgbaImage::from_fn(size.0, size.1, |x, y| {
        let i = 3 * (y as usize * size.0 as usize + x as usize);
        Rgba([rgb[i], rgb[i + 1], rgb[i + 2], 255])
    });
    write_png(path, &image).map_err(|e| failed(e.to_string()))
}

/// A text style of the registered family.
pub fn font(size: f64) -> TextStyle<'static> {
    (FAMILY, size).into_font().into()
}

/// The color of the `i`th series: distinct and readable on white (static, because
/// plotters' text styles borrow their color).
pub fn color(i: usize) -> &'static RGBColor {
    static COLORS: [RGBColor; 12] = [
        RGBColor(31, 119, 180),
        RGBColor(255, 127, 14),
        RGBColor(44, 160, 44),
        RGBColor(214, 39, 40),
        RGBColor(148, 103, 189),
        RGBColor(140, 86, 75),
        RGBColor(227, 119, 194),
        RGBColor(127, 127, 127),
        RGBColor(188, 189, 34),
        RGBColor(23, 190, 207),
        RGBColor(0, 0, 128),
        RGBColor(128, 0, 0),
    ];
    &COLORS[i % COLORS.len()]
}

/// The scenes of the measured rows, in run order.
pub fn scenes(results: &Results) -> Vec<&str> {
    let mut scenes: Vec<&str> = Vec::new();
    for row in results.rows.iter().filter(|r| r.figures.is_some()) {
        if !scenes.contains(&row.scene.as_str()) {
            scenes.push(&row.scene);
        }
    }
    scenes
}

/// `n` panels in a grid of at most two columns.
pub fn grid(n: usize) -> (usize, usize) {
    let columns = n.clamp(1, 2);
    (n.div_ceil(columns).max(1), columns)
}

/// Turns a plotters error into text.
pub fn text<E: std::fmt::Display>(e: E) -> String {
    e.to_string()
}
