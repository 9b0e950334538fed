//! pareto.png: GPU frame time against mean FLIP, one panel per scene, one numbered point
//! per pipeline (the legend on the right names the numbers) with a bar over its round
//! medians' p10 to p90, hollow when the row is flagged, and the Pareto front: the
//! pipelines no other pipeline beats on both time and error.

use plotters::prelude::*;

use super::{color, font, grid, log_axis, pipelines, scenes, text, Area, DrawResult, Legend};
use crate::commands::bench::results::Results;

const PANEL: (u32, u32) = (760, 520);
const TITLE_HEIGHT: u32 = 40;
/// What the legend says under the pipelines.
const FOOTER: &str =
    "grey: Pareto front\nbars: p10–p90 of the round medians\nhollow: flagged (spread over 5%)";

pub fn size(results: &Results) -> (u32, u32) {
    let (rows, columns) = grid(scenes(results).len());
    let legend = legend(results).size();
    (
        PANEL.0 * columns as u32 + legend.0,
        (PANEL.1 * rows as u32).max(legend.1) + TITLE_HEIGHT,
    )
}

/// One point: (pipeline index, GPU ms, mean FLIP).
type Point = (usize, f64, f64);

/// A point's spread: p10 and p90 of its round medians, and whether the row is flagged.
type Bar = (f64, f64, bool);

pub fn pareto(results: &Results, area: &Area) -> DrawResult {
    let names = pipelines(results);
    let (title, body) = area.split_vertically(TITLE_HEIGHT);
    title.titled(&heading(results), font(22.0)).map_err(text)?;
    let legend = legend(results);
    let (panels, legend_area) = body.split_horizontally(body.dim_in_pixel().0 - legend.size().0);
    let scenes = scenes(results);
    let (rows, columns) = grid(scenes.len());
    for (scene, panel) in scenes.iter().zip(panels.split_evenly((rows, columns))) {
        let (points, bars): (Vec<Point>, Vec<Bar>) = results
            .rows
            .iter()
            .filter(|r| r.scene == *scene)
            .filter_map(|r| {
                let f = r.figures.as_ref()?;
                let time = f.gpu_frame_ms.as_ref()?;
                let flip = f.image_error.as_ref()?.flip_mean;
                let index = names.iter().position(|n| *n == r.pipeline)?;
                Some((
                    (index, time.median, flip),
                    (time.p10, time.p90, f.flag.is_some()),
                ))
            })
            .unzip();
        scene_panel(&panel, scene, &points, &bars)?;
    }
    legend.draw(&legend_area)
}

/// The pipelines by the numbers their points carry, and what the marks mean.
fn legend(results: &Results) -> Legend<'static> {
    Legend {
        title: "pipelines",
        labels: pipelines(results)
            .iter()
            .enumerate()
            .map(|(i, name)| format!("{} {name}", i + 1))
            .collect(),
        footer: Some(FOOTER),
    }
}

fn heading(results: &Results) -> String {
    format!(
        "Speed vs error: {} at {}x{} (lower left is better)",
        results.adapter.name, results.resolution[0], results.resolution[1]
    )
}

fn scene_panel(area: &Area, scene: &str, points: &[Point], bars: &[Bar]) -> DrawResult {
    if points.is_empty() {
        area.titled(&format!("{scene}: no time and error measured"), font(18.0))
            .map_err(text)?;
        return Ok(());
    }
    let (lo, hi) = bars.iter().fold((f64::MAX, f64::MIN), |(lo, hi), b| {
        (lo.min(b.0), hi.max(b.1))
    });
    let top = points.iter().map(|p| p.2).fold(0.0, f64::max).max(1e-3) * 1.15;
    // Enough decimals that labels a tenth of the axis apart differ (at least 3).
    let digits = (-(top / 10.0).log10()).ceil().max(3.0) as usize;
    let mut chart = ChartBuilder::on(area)
        .caption(scene, font(18.0))
        .margin(12)
        .x_label_area_size(46)
        .y_label_area_size(64)
        .build_cartesian_2d(log_axis(lo / 1.3..hi * 1.3), 0.0..top)
        .map_err(text)?;
    chart
        .configure_mesh()
        .x_desc("GPU frame time, ms (median; log scale)")
        .y_desc("mean FLIP vs reference")
        .label_style(font(14.0))
        .axis_desc_style(font(15.0))
        .x_labels(8)
        .x_label_formatter(&|v| ms(*v))
        .y_label_formatter(&|v| format!("{v:.digits$}"))
        .draw()
        .map_err(text)?;
    chart
        .draw_series(LineSeries::new(
            front_steps(points),
            ShapeStyle::from(&RGBColor(150, 150, 150)).stroke_width(2),
        ))
        .map_err(text)?;
    chart
        .draw_series(
            points
                .iter()
                .zip(bars)
                .map(|(&(i, _, flip), &(p10, p90, _))| {
                    PathElement::new([(p10, flip), (p90, flip)], color(i).stroke_width(2))
                }),
        )
        .map_err(text)?;
    chart
        .draw_series(
            points
                .iter()
                .zip(bars)
                .map(|(&(i, ms, flip), &(.., flagged))| {
                    let label = font(15.0).color(color(i));
                    let dot = match flagged {
                        true => ShapeStyle::from(color(i)).stroke_width(2),
                        false => color(i).filled(),
                    };
                    EmptyElement::at((ms, flip))
                + Circle::new((0, 0), 6, dot)
                // Alternating above and below keeps neighbours' numbers apart.
                + Text::new(format!("{}", i + 1), (8, if i % 2 == 0 { -18 } else { 4 }), label)
                }),
        )
        .map_err(text)?;
    Ok(())
}

/// Milliseconds with the digits that matter at their size.
fn ms(v: f64) -> String {
    match v {
        v if v >= 10.0 => format!("{v:.0}"),
        v if v >= 1.0 => format!("{v:.1}"),
        v => format!("{v:.2}"),
    }
}

/// The Pareto front as a staircase: from the fastest point, each next point that has less
/// error than every faster one, joined by horizontal-then-vertical steps.
fn front_steps(points: &[Point]) -> Vec<(f64, f64)> {
    let mut sorted = points.to_vec();
    sorted.sort_by(|a, b| a.1.total_cmp(&b.1).then(a.2.total_cmp(&b.2)));
    let mut steps: Vec<(f64, f64)> = Vec::new();
    let mut best = f64::MAX;
    for (_, ms, flip) in sorted {
        if flip < best {
            if let Some(&(_, last)) = steps.last() {
                steps.push((ms, last));
            }
            steps.push((ms, flip));
            best = flip;
        }
    }
    steps
}

#[cfg(test)]
mod tests {
    use super::front_steps;

    #[test]
    fn the_front_keeps_points_no_other_beats_on_both() {
        // b is beaten by a (faster and better); c is slower but better than a.
        let points = [(0, 1.0, 0.5), (1, 2.0, 0.6), (2, 3.0, 0.1)];
        assert_eq!(front_steps(&points), [(1.0, 0.5), (3.0, 0.5), (3.0, 0.1)]);
    }
}
