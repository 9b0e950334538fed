//! results.md: the run's setting, then per scene one table a person reads (one row per
//! pipeline, error rows included) and the per-pass GPU times.

use std::fmt::Write;

use graph_core::explain::bytes;

use super::results::{Figures, Results, Row};

pub fn markdown(results: &Results) -> String {
    let mut md = String::new();
    let r = results;
    let _ = writeln!(md, "# rgraph bench\n");
    let _ = writeln!(md, "`{}`\n", r.command);
    let _ = writeln!(
        md,
        "- machine: {} ({}, {} cores)\n- adapter: {} [{} {}], {} {}\n- resolution: {}x{}, \
         {} measured frames after {} warmup\n- commit: {}\n- time: {}",
        r.machine.hostname,
        r.machine.cpu,
        r.machine.cpu_cores,
        r.adapter.name,
        r.adapter.driver,
        r.adapter.driver_info,
        r.adapter.backend,
        r.adapter.device_type,
        r.resolution[0],
        r.resolution[1],
        r.frames,
        r.warmup,
        r.git_commit,
        r.timestamp,
    );
    for note in &r.notes {
        let _ = writeln!(md, "- note: {note}");
    }
    let mut scenes: Vec<&str> = r.rows.iter().map(|row| row.scene.as_str()).collect();
    scenes.dedup();
    for scene in scenes {
        let rows: Vec<&Row> = r.rows.iter().filter(|row| row.scene == scene).collect();
        let _ = writeln!(md, "\n## {scene}\n");
        md.push_str(&scene_table(&rows));
        if rows.iter().any(|row| row.figures.is_some()) {
            md.push_str(&pass_table(&rows));
        }
    }
    md.push_str(LEGEND);
    md
}

const HEADER: &str = "| pipeline | GPU ms | p10–p90 | × noaa | CPU rec. ms | memory | pooled | \
                      G-buf B/sample | edge px | shaded/px |\n\
                      |---|--:|--:|--:|--:|--:|--:|--:|--:|--:|\n";

fn scene_table(rows: &[&Row]) -> String {
    let mut md = String::from(HEADER);
    for row in rows {
        let cells = match (&row.figures, &row.message) {
            (Some(f), _) => figure_cells(f),
            (None, message) => vec![format!(
                "error: {}",
                message.as_deref().unwrap_or("?").replace('\n', " ")
            )],
        };
        let _ = writeln!(md, "| {} | {} |", row.pipeline, cells.join(" | "));
    }
    md
}

fn figure_cells(f: &Figures) -> Vec<String> {
    let gpu = f.gpu_frame_ms.as_ref();
    vec![
        gpu.map_or("-".into(), |s| ms(s.median)),
        gpu.map_or("-".into(), |s| format!("{}–{}", ms(s.p10), ms(s.p90))),
        f.ratio_to_noaa.map_or("-".into(), |r| format!("{r:.2}")),
        f.cpu_record_ms
            .as_ref()
            .map_or("-".into(), |s| ms(s.median)),
        bytes(f.memory.logical_bytes),
        bytes(f.memory.physical_bytes),
        f.memory
            .gbuffer_bytes_per_sample
            .map_or("-".into(), |b| b.to_string()),
        f.work
            .edge_pixel_share
            .map_or("-".into(), |s| format!("{:.1}%", s * 100.0)),
        f.work
            .shaded_samples_per_pixel
            .map_or("-".into(), |s| format!("{s:.2}")),
    ]
}

/// Median GPU ms of each pass, one line per pipeline.
fn pass_table(rows: &[&Row]) -> String {
    let mut md = String::from("\n| pipeline | GPU ms per pass (median) |\n|---|---|\n");
    for row in rows {
        let Some(f) = &row.figures else { continue };
        let passes: Vec<String> = f
            .passes
            .iter()
            .map(|p| {
                let t = p.gpu_ms.as_ref().map_or("-".into(), |s| ms(s.median));
                format!("{} {t}", p.name)
            })
            .collect();
        let _ = writeln!(md, "| {} | {} |", row.pipeline, passes.join(", "));
    }
    md
}

fn ms(value: f64) -> String {
    if value >= 100.0 {
        format!("{value:.0}")
    } else if value >= 10.0 {
        format!("{value:.1}")
    } else {
        format!("{value:.2}")
    }
}

const LEGEND: &str = "\n\
GPU ms: median GPU frame time from timestamps (first pass's begin to last pass's end), with \
the 10th–90th percentile over the measured frames. × noaa: median over deferred_noaa's on \
the same scene in this run. CPU rec.: CPU time to record all passes. memory / pooled: \
bytes of the graph's textures on their own and after sharing. G-buf B/sample: bytes per \
sample of the gbuffer pass's color targets. edge px: pixels the pipeline's debug.edges \
marks; shaded/px: shading invocations per pixel (edge pixels once per sample, others once; \
pipelines without debug.edges by their kind, see results.json). On lavapipe times are CPU \
rasterisation: compare ratios within one run only.\n";
