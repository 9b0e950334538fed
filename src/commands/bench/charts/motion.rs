//! motion.png (`bench --motion`): each pipeline's FLIP against the reference frame by
//! frame, one panel per scene: frame 0 is the last still frame (the temporal filters'
//! history full), frames 1 to N the moving ones, whose mean is the table's sequence FLIP.

use plotters::prelude::*;

use super::{distinct, font, grid, marked_lines, text, tick, Area, DrawResult, Legend};

const PANEL: (u32, u32) = (760, 480);
const TITLE_HEIGHT: u32 = 40;

/// One pipeline's series on one scene: FLIP per frame, from the last still one.
pub struct Series<'a> {
    pub scene: &'a str,
    pub pipeline: &'a str,
    pub flips: Vec<f64>,
}

pub fn size(series: &[Series<'_>]) -> (u32, u32) {
    let (rows, columns) = grid(scenes(series).len());
    let legend = legend(series).size();
    (
        PANEL.0 * columns as u32 + legend.0,
        (PANEL.1 * rows as u32).max(legend.1) + TITLE_HEIGHT,
    )
}

/// Draws the chart titled `title` (the adapter, the size and the motion).
pub fn motion(series: &[Series<'_>], title: &str, area: &Area) -> DrawResult {
    let (title_area, body) = area.split_vertically(TITLE_HEIGHT);
    title_area.titled(title, font(17.0)).map_err(text)?;
    let legend = legend(series);
    let (panel_area, legend_area) =
        body.split_horizontally(body.dim_in_pixel().0 - legend.size().0);
    let scenes = scenes(series);
    let names = pipelines(series);
    for (scene, panel) in scenes
        .iter()
        .zip(panel_area.split_evenly(grid(scenes.len())))
    {
        let lines: Vec<Vec<(f64, f64)>> = names
            .iter()
            .map(|name| {
                series
                    .iter()
                    .filter(|s| s.scene == *scene && s.pipeline == *name)
                    .flat_map(|s| s.flips.iter().enumerate().map(|(i, &f)| (i as f64, f)))
                    .collect()
            })
            .collect();
        panel_chart(&panel, scene, &lines)?;
    }
    legend.draw(&legend_area)
}

fn scenes<'a>(series: &[Series<'a>]) -> Vec<&'a str> {
    distinct(series.iter().map(|s| s.scene))
}

/// The pipelines in the order they first appear: the index picks the color.
fn pipelines<'a>(series: &[Series<'a>]) -> Vec<&'a str> {
    distinct(series.iter().map(|s| s.pipeline))
}

fn legend(series: &[Series<'_>]) -> Legend<'static> {
    Legend {
        title: "pipelines",
        labels: pipelines(series).iter().map(|n| n.to_string()).collect(),
        footer: Some("frame 0: the last still one"),
    }
}

fn panel_chart(area: &Area, scene: &str, lines: &[Vec<(f64, f64)>]) -> DrawResult {
    let points = || lines.iter().flatten();
    let frames = points().map(|p| p.0).fold(1.0, f64::max);
    let top = points().map(|p| p.1).fold(0.0, f64::max) * 1.1;
    let mut chart = ChartBuilder::on(area)
        .caption(scene, font(18.0))
        .margin(12)
        .x_label_area_size(46)
        .y_label_area_size(64)
        .build_cartesian_2d(0.0..frames, 0.0..top.max(1e-3))
        .map_err(text)?;
    chart
        .configure_mesh()
        .x_desc("frame")
        .y_desc("FLIP against the reference's frame")
        .label_style(font(14.0))
        .axis_desc_style(font(15.0))
        .x_label_formatter(&|v| tick(*v))
        .y_label_formatter(&|v| tick(*v))
        .draw()
        .map_err(text)?;
    marked_lines(&mut chart, lines, 3)
}
