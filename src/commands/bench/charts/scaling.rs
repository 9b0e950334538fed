//! scaling.png: how cost grows with the swept parameter. For each scene (the sweeps over a
//! built-in scene's parameter have one: they differ only in that parameter) three panels:
//! the median GPU frame time, the median CPU time to record the frame, and the memory the
//! plan, its passes and the scene's geometry hold; one line per pipeline, both axes
//! logarithmic (resolution in megapixels).

use plotters::prelude::*;

use super::{
    count, distinct, font, grid, log_axis, marked_lines, pipelines, text, tick, Area, DrawResult,
    Legend,
};
use crate::cli::Sweep;
use crate::commands::bench::results::{Results, Row};

const PANEL: (u32, u32) = (760, 520);
const TITLE_HEIGHT: u32 = 40;

/// What a panel plots against the swept parameter.
#[derive(Clone, Copy)]
enum Metric {
    GpuFrame,
    CpuRecord,
    Memory,
}

const METRICS: [Metric; 3] = [Metric::GpuFrame, Metric::CpuRecord, Metric::Memory];

impl Metric {
    fn axis(self) -> &'static str {
        match self {
            Metric::GpuFrame => "GPU frame time, ms (median; log scale)",
            Metric::CpuRecord => "CPU record time, ms (median; log scale)",
            Metric::Memory => "plan, pass and geometry memory, MiB (log scale)",
        }
    }

    /// The row's figure; memory adds the geometry its scene uploads (`results.scenes`).
    fn of(self, row: &Row, results: &Results) -> Option<f64> {
        let figures = row.figures.as_ref()?;
        match self {
            Metric::GpuFrame => Some(figures.gpu_frame_ms.as_ref()?.median),
            Metric::CpuRecord => Some(figures.cpu_record_ms.as_ref()?.median),
            Metric::Memory => {
                let geometry = results
                    .scenes
                    .iter()
                    .find(|s| s.scene == row.scene)
                    .and_then(|s| s.size.as_ref())
                    .map_or(0, |size| size.geometry_bytes);
                let bytes = figures.memory.physical_bytes + figures.memory.pass_bytes + geometry;
                Some(bytes as f64 / (1u64 << 20) as f64)
            }
        }
    }
}

pub fn size(results: &Results) -> (u32, u32) {
    let (rows, columns) = grid(panels(results).len() * METRICS.len());
    let legend = legend(results).size();
    (
        PANEL.0 * columns as u32 + legend.0,
        (PANEL.1 * rows as u32).max(legend.1) + TITLE_HEIGHT,
    )
}

pub fn scaling(results: &Results, sweep: Sweep, area: &Area) -> DrawResult {
    let (title, body) = area.split_vertically(TITLE_HEIGHT);
    title
        .titled(
            &match sweep {
                Sweep::Resolution => {
                    format!("Cost vs {}: {}", parameter(sweep), results.adapter.name)
                }
                _ => format!(
                    "Cost vs {}: {} at {}x{}",
                    parameter(sweep),
                    results.adapter.name,
                    results.resolution[0],
                    results.resolution[1]
                ),
            },
            font(22.0),
        )
        .map_err(text)?;
    let legend = legend(results);
    let (panel_area, legend_area) =
        body.split_horizontally(body.dim_in_pixel().0 - legend.size().0);
    let names = pipelines(results);
    let panels: Vec<(&str, Metric)> = panels(results)
        .into_iter()
        .flat_map(|group| METRICS.map(|metric| (group, metric)))
        .collect();
    let (rows, columns) = grid(panels.len());
    for (&(group, metric), panel) in panels.iter().zip(panel_area.split_evenly((rows, columns))) {
        let lines: Vec<Vec<(f64, f64)>> = names
            .iter()
            .map(|name| {
                results
                    .rows
                    .iter()
                    .filter(|r| r.pipeline == *name && scene_group(r) == group)
                    .filter_map(|r| Some((x(r, sweep)?, metric.of(r, results)?)))
                    .collect()
            })
            .collect();
        panel_chart(&panel, group, sweep, metric, &lines)?;
    }
    legend.draw(&legend_area)
}

fn legend(results: &Results) -> Legend<'static> {
    Legend {
        title: "pipelines",
        labels: pipelines(results).iter().map(|n| n.to_string()).collect(),
        footer: None,
    }
}

fn parameter(sweep: Sweep) -> &'static str {
    match sweep {
        Sweep::Triangles => "triangle count",
        Sweep::Meshes => "mesh count",
        Sweep::Lights => "light count",
        Sweep::Resolution => "resolution",
        Sweep::Samples => "MSAA samples",
    }
}

/// The scene without its parameters: "builtin:lights?count=64" → "builtin:lights".
fn scene_group(row: &Row) -> &str {
    row.scene.split('?').next().unwrap_or(&row.scene)
}

fn panels(results: &Results) -> Vec<&str> {
    distinct(results.rows.iter().map(scene_group))
}

/// Triangles, meshes, lights and samples as counts, resolution as megapixels.
fn x(row: &Row, sweep: Sweep) -> Option<f64> {
    let point = row.sweep.as_ref()?;
    Some(match sweep {
        Sweep::Resolution => {
            let (w, h) = point.label.split_once('x')?;
            w.parse::<f64>().ok()? * h.parse::<f64>().ok()? / 1e6
        }
        _ => point.value as f64,
    })
}

fn panel_chart(
    area: &Area,
    group: &str,
    sweep: Sweep,
    metric: Metric,
    lines: &[Vec<(f64, f64)>],
) -> DrawResult {
    let points = || lines.iter().flatten();
    if points().next().is_none() {
        area.titled(&format!("{group}: nothing measured"), font(18.0))
            .map_err(text)?;
        return Ok(());
    }
    let bounds = |values: Vec<f64>| {
        let lo = values.iter().copied().fold(f64::MAX, f64::min);
        let hi = values.iter().copied().fold(f64::MIN, f64::max);
        (lo / 1.3)..(hi * 1.3)
    };
    let xs = bounds(points().map(|p| p.0).collect());
    let ys = bounds(points().map(|p| p.1).collect());
    let mut chart = ChartBuilder::on(area)
        .caption(group, font(18.0))
        .margin(12)
        .x_label_area_size(46)
        .y_label_area_size(64)
        .build_cartesian_2d(log_axis(xs), log_axis(ys))
        .map_err(text)?;
    let x_desc = match sweep {
        Sweep::Triangles => "triangles (log scale)",
        Sweep::Meshes => "meshes (log scale)",
        Sweep::Lights => "lights (log scale)",
        Sweep::Resolution => "megapixels (log scale)",
        Sweep::Samples => "samples per pixel (log scale)",
    };
    chart
        .configure_mesh()
        .x_desc(x_desc)
        .y_desc(metric.axis())
        .label_style(font(14.0))
        .axis_desc_style(font(15.0))
        .x_label_formatter(&|v| count(*v))
        .y_label_formatter(&|v| tick(*v))
        .draw()
        .map_err(text)?;
    marked_lines(&mut chart, lines, 4)
}
