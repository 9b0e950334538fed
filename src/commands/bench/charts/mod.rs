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
use super::results::{Results, Row};
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
    distinct(measured(results).map(|r| r.scene.as_str()))
}

/// The measured pipelines in the order they first appear: the index picks the color.
pub fn pipelines(results: &Results) -> Vec<&str> {
    distinct(measured(results).map(|r| r.pipeline.as_str()))
}

fn measured(results: &Results) -> impl Iterator<Item = &Row> {
    results.rows.iter().filter(|r| r.figures.is_some())
}

/// `items` without repeats, in the order they first appear.
pub fn distinct<'a>(items: impl Iterator<Item = &'a str>) -> Vec<&'a str> {
    let mut seen: Vec<&str> = Vec::new();
    for item in items {
        if !seen.contains(&item) {
            seen.push(item);
        }
    }
    seen
}

/// A legend column: `title`, then a square of the `i`th color before each label, then
/// `footer` when given.
pub fn legend(area: &Area, title: &str, labels: &[String], footer: Option<&str>) -> DrawResult {
    area.draw(&Text::new(title.to_string(), (10, 20), font(17.0)))
        .map_err(text)?;
    for (i, label) in labels.iter().enumerate() {
        let y = 50 + 24 * i as i32;
        area.draw(&Rectangle::new([(10, y), (26, y + 16)], color(i).filled()))
            .map_err(text)?;
        area.draw(&Text::new(label.clone(), (34, y), font(15.0)))
            .map_err(text)?;
    }
    // The footer's lines under the labels.
    for (i, line) in footer.into_iter().flat_map(str::lines).enumerate() {
        let y = 60 + 24 * (labels.len() + i) as i32;
        area.draw(&Text::new(line.to_string(), (10, y), font(15.0)))
            .map_err(text)?;
    }
    Ok(())
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
