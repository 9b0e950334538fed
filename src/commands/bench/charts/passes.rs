//! passes.png: per scene, one horizontal bar per pipeline, stacked from its passes' median
//! GPU times in execution order; a pass name keeps its color across pipelines and scenes.

use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::{color, distinct, font, grid, scenes, text, tick, Area, DrawResult, Legend};
use crate::commands::bench::results::{Results, Row};

const PANEL_WIDTH: u32 = 900;
const ROW_HEIGHT: u32 = 30;
const PANEL_EXTRA: u32 = 150;
const TITLE_HEIGHT: u32 = 40;

pub fn size(results: &Results) -> (u32, u32) {
    let scenes = scenes(results);
    let (rows, columns) = grid(scenes.len());
    let bars = scenes
        .iter()
        .map(|s| measured(results, s).len())
        .max()
        .unwrap_or(1) as u32;
    let panels = (ROW_HEIGHT * bars + PANEL_EXTRA) * rows as u32;
    let legend = legend(results).size();
    (
        PANEL_WIDTH * columns as u32 + legend.0,
        panels.max(legend.1) + TITLE_HEIGHT,
    )
}

pub fn passes(results: &Results, area: &Area) -> DrawResult {
    let names = pass_names(results);
    let (title, body) = area.split_vertically(TITLE_HEIGHT);
    title
        .titled(
            &format!(
                "GPU time per pass (median ms): {} at {}x{}",
                results.adapter.name, results.resolution[0], results.resolution[1]
            ),
            font(22.0),
        )
        .map_err(text)?;
    let legend = legend(results);
    let (panels, legend_area) = body.split_horizontally(body.dim_in_pixel().0 - legend.size().0);
    let scenes = scenes(results);
    let (rows, columns) = grid(scenes.len());
    for (scene, panel) in scenes.iter().zip(panels.split_evenly((rows, columns))) {
        scene_panel(&panel, scene, &measured(results, scene), &names)?;
    }
    legend.draw(&legend_area)
}

fn legend(results: &Results) -> Legend<'static> {
    Legend {
        title: "passes",
        labels: pass_names(results).iter().map(|n| n.to_string()).collect(),
        footer: None,
    }
}

fn measured<'a>(results: &'a Results, scene: &str) -> Vec<&'a Row> {
    results
        .rows
        .iter()
        .filter(|r| r.scene == scene && r.figures.is_some())
        .collect()
}

/// Every pass name in order of first appearance: its index picks its color.
fn pass_names(results: &Results) -> Vec<&str> {
    let figures = results.rows.iter().filter_map(|r| r.figures.as_ref());
    distinct(figures.flat_map(|f| f.passes.iter().map(|p| p.name.as_str())))
}

fn scene_panel(area: &Area, scene: &str, rows: &[&Row], names: &[&str]) -> DrawResult {
    // (bar index, pass name index, start ms, end ms) of every bar segment; the first
    // pipeline's bar is the top one (bar index 0 is at the bottom).
    let mut segments = Vec::new();
    let mut totals = Vec::new();
    for (row_index, row) in rows.iter().enumerate() {
        let i = rows.len() - 1 - row_index;
        let mut at = 0.0;
        for pass in row.figures.iter().flat_map(|f| &f.passes) {
            let ms = pass.gpu_ms.as_ref().map_or(0.0, |s| s.median);
            let name = names.iter().position(|n| *n == pass.name).unwrap_or(0);
            segments.push((i, name, at, at + ms));
            at += ms;
        }
        totals.push((i, at));
    }
    let end = axis_end(totals.iter().map(|t| t.1).collect());
    let labels: Vec<&str> = rows.iter().rev().map(|r| r.pipeline.as_str()).collect();
    // Two units of height per bar, labelled at its middle (an odd number): a segmented
    // axis would add an empty segment above the last bar, and plotters formats no
    // floating-point axis with chosen key points.
    let bars = rows.len() as i32;
    let middles: Vec<i32> = (0..bars).map(|i| 2 * i + 1).collect();
    let mut chart = ChartBuilder::on(area)
        .caption(scene, font(18.0))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(250)
        .build_cartesian_2d(0.0..end, (0..2 * bars).with_key_points(middles))
        .map_err(text)?;
    chart
        .configure_mesh()
        .disable_y_mesh()
        .x_desc("GPU ms (median)")
        .x_label_formatter(&|v| tick(*v))
        .label_style(font(14.0))
        .axis_desc_style(font(15.0))
        .y_label_formatter(&|v| {
            labels
                .get((*v / 2) as usize)
                .map_or(String::new(), |s| s.to_string())
        })
        .draw()
        .map_err(text)?;
    chart
        .draw_series(
            segments
                .iter()
                .filter(|s| s.2 < end)
                .map(|&(i, n, x0, x1)| {
                    let mut bar = Rectangle::new(
                        [(x0, 2 * i as i32), (x1.min(end), 2 * i as i32 + 2)],
                        color(n).filled(),
                    );
                    bar.set_margin(4, 4, 0, 0);
                    bar
                }),
        )
        .map_err(text)?;
    // Bars cut at the axis end say how long they are.
    let label = font(14.0)
        .color(&WHITE)
        .pos(Pos::new(HPos::Right, VPos::Center));
    chart
        .draw_series(totals.iter().filter(|t| t.1 > end).map(|&(i, total)| {
            Text::new(
                format!("{total:.0} ms >"),
                (end * 0.99, 2 * i as i32 + 1),
                label.clone(),
            )
        }))
        .map_err(text)?;
    Ok(())
}

/// Where the time axis ends: past the longest bar, unless one bar is more than 3 times
/// the next (the reference usually), which is then cut so the others stay readable.
fn axis_end(mut totals: Vec<f64>) -> f64 {
    totals.sort_by(|a, b| b.total_cmp(a));
    match totals.as_slice() {
        [first, second, ..] if *first > 3.0 * second => second * 1.4,
        [first, ..] => first * 1.05,
        [] => 1.0,
    }
    .max(1e-3)
}

#[cfg(test)]
mod tests {
    use super::axis_end;

    #[test]
    fn one_bar_far_longer_than_the_rest_is_cut() {
        assert_eq!(axis_end(vec![10.0, 100.0, 20.0]), 20.0 * 1.4);
        assert_eq!(axis_end(vec![10.0, 20.0]), 20.0 * 1.05);
        assert_eq!(axis_end(vec![]), 1.0);
    }
}
