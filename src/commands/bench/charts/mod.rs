//! The charts a bench writes, drawn with plotters into memory and saved through the same
//! PNG writer as the images. Text uses the DejaVu Sans file committed under assets/fonts,
//! registered with plotters' ab_glyph backend, so no system font is needed.

mod motion;
mod pareto;
mod passes;
mod scaling;

use std::path::Path;
use std::sync::Once;

use image::{Rgba, RgbaImage};
use plotters::coord::combinators::{LogCoord, WithKeyPoints};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::{register_font, FontStyle};

use super::error::BenchError;
use super::results::{Results, Row};
use crate::commands::write_png;

pub use motion::Series;
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

/// Writes motion.png (`bench --motion`) into `out`: `series`' FLIP frame by frame, under
/// `title`.
pub fn write_motion(series: &[Series<'_>], title: &str, out: &Path) -> Result<(), BenchError> {
    draw_png(&out.join("motion.png"), motion::size(series), |area| {
        motion::motion(series, title, area)
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
/// plotters' text styles borrow their color). Twenty, so that the every-4x part's 13
/// pipelines and 15 passes repeat none.
pub fn color(i: usize) -> &'static RGBColor {
    static COLORS: [RGBColor; 20] = [
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
        RGBColor(0, 128, 128),
        RGBColor(218, 165, 32),
        RGBColor(0, 0, 0),
        RGBColor(128, 128, 0),
        RGBColor(106, 61, 154),
        RGBColor(251, 154, 153),
        RGBColor(166, 206, 227),
        RGBColor(178, 223, 138),
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

/// Where a legend's first label sits, how far apart its lines are, and where a label's
/// text starts (after its color square), in pixels.
const LEGEND_TOP: u32 = 50;
const LEGEND_LINE: u32 = 24;
const LEGEND_TEXT_X: u32 = 34;

/// A legend column beside a chart's panels: `title`, then a square of the `i`th color
/// before each label, then `footer`'s lines when given. A chart sizes its image with
/// [`Legend::size`] so that no label is cut.
pub struct Legend<'a> {
    pub title: &'a str,
    pub labels: Vec<String>,
    pub footer: Option<&'a str>,
}

impl Legend<'_> {
    /// The width and height the legend draws in. The width estimates DejaVu Sans at 15
    /// pixels as 9 pixels a character (its widest lowercase letters are about 9.4, its
    /// average nearer 8), which plotters cannot measure before the font is registered.
    pub fn size(&self) -> (u32, u32) {
        let lines = self
            .labels
            .iter()
            .map(|l| LEGEND_TEXT_X as usize + 9 * l.chars().count());
        let footer = self.footer.into_iter().flat_map(str::lines);
        let footer_width = footer.clone().map(|l| 10 + 9 * l.chars().count());
        let width = lines.chain(footer_width).max().unwrap_or(0) as u32 + 20;
        let rows = self.labels.len() + footer.count() + 1;
        (width, LEGEND_TOP + 10 + LEGEND_LINE * rows as u32)
    }

    pub fn draw(&self, area: &Area) -> DrawResult {
        area.draw(&Text::new(self.title.to_string(), (10, 20), font(17.0)))
            .map_err(text)?;
        for (i, label) in self.labels.iter().enumerate() {
            let y = (LEGEND_TOP + LEGEND_LINE * i as u32) as i32;
            area.draw(&Rectangle::new([(10, y), (26, y + 16)], color(i).filled()))
                .map_err(text)?;
            area.draw(&Text::new(
                label.clone(),
                (LEGEND_TEXT_X as i32, y),
                font(15.0),
            ))
            .map_err(text)?;
        }
        // The footer's lines under the labels.
        let footer = self.footer.into_iter().flat_map(str::lines);
        for (i, line) in footer.enumerate() {
            let y = LEGEND_TOP + 10 + LEGEND_LINE * (self.labels.len() + i) as u32;
            area.draw(&Text::new(line.to_string(), (10, y as i32), font(15.0)))
                .map_err(text)?;
        }
        Ok(())
    }
}

/// An axis label: the value with at most 3 decimals and no trailing zeros, so that ticks
/// half a unit apart read 0.5, 1, 1.5 rather than being rounded to the same number.
pub fn tick(v: f64) -> String {
    format!("{v:.3}")
        .trim_end_matches('0')
        .trim_end_matches('.')
        .to_owned()
}

/// A count as an axis label: 20k, 1.5M, 100M; under a thousand as [`tick`] writes it. A
/// sweep over decades of triangles labels 1, 2 and 5 times each, and written out in full
/// the millions ran into each other.
pub fn count(v: f64) -> String {
    match v.abs() {
        a if a >= 1e9 => format!("{}G", tick(v / 1e9)),
        a if a >= 1e6 => format!("{}M", tick(v / 1e6)),
        a if a >= 1e3 => format!("{}k", tick(v / 1e3)),
        _ => tick(v),
    }
}

/// A logarithmic axis over `range` whose labels are 1, 2 and 5 times each power of ten
/// inside it, or 1 to 9 times it where those are fewer than three: plotters labels only
/// the powers of ten, which leaves an axis spanning less than a decade without numbers.
pub fn log_axis(range: std::ops::Range<f64>) -> WithKeyPoints<LogCoord<f64>> {
    let ticks = |steps: &[f64]| {
        let mut ticks = Vec::new();
        let mut decade = 10f64.powf(range.start.max(f64::MIN_POSITIVE).log10().floor());
        while decade <= range.end {
            let inside = steps
                .iter()
                .map(|s| decade * s)
                .filter(|v| range.contains(v));
            ticks.extend(inside);
            decade *= 10.0;
        }
        ticks
    };
    let coarse = ticks(&[1.0, 2.0, 5.0]);
    let ticks = match coarse.len() {
        3.. => coarse,
        _ => ticks(&[1.0, 1.5, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0]),
    };
    range.log_scale().with_key_points(ticks)
}

/// `n` panels in a grid of at most two columns.
pub fn grid(n: usize) -> (usize, usize) {
    let columns = n.clamp(1, 2);
    (n.div_ceil(columns).max(1), columns)
}

/// Turns a plotters error into text.
/// Each of `lines` drawn in `chart` in the i-th colour, a mark of `radius` pixels at each
/// point (the motion and scaling charts).
pub fn marked_lines<'a, X, Y>(
    chart: &mut ChartContext<'a, BitMapBackend<'a>, Cartesian2d<X, Y>>,
    lines: &[Vec<(f64, f64)>],
    radius: i32,
) -> DrawResult
where
    X: Ranged<ValueType = f64>,
    Y: Ranged<ValueType = f64>,
{
    for (i, line) in lines.iter().enumerate() {
        chart
            .draw_series(LineSeries::new(
                line.iter().copied(),
                color(i).stroke_width(2),
            ))
            .map_err(text)?;
        chart
            .draw_series(
                line.iter()
                    .map(|&p| Circle::new(p, radius, color(i).filled())),
            )
            .map_err(text)?;
    }
    Ok(())
}

pub fn text<E: std::fmt::Display>(e: E) -> String {
    e.to_string()
}

#[cfg(test)]
mod tests {
    use plotters::coord::ranged1d::{BoldPoints, Ranged};

    use super::{color, count, log_axis, tick, Legend};

    #[test]
    fn the_first_twenty_series_have_colors_of_their_own() {
        let colors: Vec<_> = (0..20)
            .map(|i| {
                let c = color(i);
                (c.0, c.1, c.2)
            })
            .collect();
        for (i, a) in colors.iter().enumerate() {
            assert!(
                !colors[..i].contains(a),
                "series {i} repeats a color: {a:?}"
            );
        }
    }

    #[test]
    fn a_log_axis_less_than_a_decade_wide_still_has_labels() {
        let labels = |lo, hi| log_axis(lo..hi).key_points(BoldPoints(100));
        assert_eq!(labels(1.2, 60.0), [2.0, 5.0, 10.0, 20.0, 50.0]);
        assert_eq!(labels(134.0, 282.0), [150.0, 200.0]);
        assert_eq!(labels(0.9, 1.1), [0.9, 1.0]);
    }

    #[test]
    fn ticks_half_a_unit_apart_read_differently() {
        let labels: Vec<String> = (0..7).map(|i| tick(f64::from(i) * 0.5)).collect();
        assert_eq!(labels, ["0", "0.5", "1", "1.5", "2", "2.5", "3"]);
        assert_eq!(tick(0.1 + 0.2), "0.3");
        assert_eq!(tick(120.0), "120");
        assert_eq!(tick(0.0126), "0.013");
    }

    #[test]
    fn counts_read_in_thousands_millions_and_billions() {
        let labels: Vec<String> = [5.0, 999.0, 2e4, 1.5e6, 1e8, 2e9].map(count).to_vec();
        assert_eq!(labels, ["5", "999", "20k", "1.5M", "100M", "2G"]);
    }

    #[test]
    fn a_legend_makes_room_for_every_label_and_its_longest_line() {
        let legend = |labels: &[&str], footer| Legend {
            title: "passes",
            labels: labels.iter().map(|l| l.to_string()).collect(),
            footer,
        };
        let seven = legend(&["a"; 7], None).size();
        assert_eq!(legend(&["a"; 8], None).size().1 - seven.1, 24);
        assert_eq!(
            legend(&["a"; 7], Some("x\ny\nz")).size().1,
            legend(&["a"; 10], None).size().1
        );
        // The last label's square (16 pixels from its line's top) lies inside.
        assert!(seven.1 >= 50 + 24 * 6 + 16);
        let long = "particle depth (hardware raster)";
        assert!(legend(&["a", long], None).size().0 >= 34 + 8 * long.len() as u32);
    }
}
