//! `explain --timings results.json`: a bench's per-pass times for the page, from the row of
//! the explained pipeline (and scene). Reads only what the page shows of what
//! `bench/results.rs` writes, fields every schema so far has: `rows[]` with `scene`,
//! `pipeline`, `file`, `status`, `sweep`, `message` and `figures.passes[]` of
//! `name`, `gpu_ms.median`, `cpu_ms.median`; `resolution` and `adapter.name`.

use std::path::Path;

use rgraph_core::bounded_read::read_text;
use rgraph_core::explain::page::{PassTime, Timings};
use serde::Deserialize;

use crate::commands::CommandError;

/// A results.json larger than this is not one the bench wrote for a few pipelines.
const MAX_BYTES: u64 = 64 << 20;

#[derive(Deserialize)]
struct Results {
    resolution: [u32; 2],
    adapter: Adapter,
    rows: Vec<Row>,
}

#[derive(Deserialize)]
struct Adapter {
    name: String,
}

#[derive(Deserialize)]
struct Row {
    scene: String,
    pipeline: String,
    file: String,
    status: String,
    sweep: Option<serde_json::Value>,
    message: Option<String>,
    figures: Option<Figures>,
}

#[derive(Deserialize)]
struct Figures {
    gpu_frame_ms: Option<Median>,
    cpu_record_ms: Option<Median>,
    passes: Vec<PassFigures>,
}

#[derive(Deserialize)]
struct PassFigures {
    name: String,
    gpu_ms: Option<Median>,
    cpu_ms: Option<Median>,
}

#[derive(Deserialize)]
struct Median {
    median: f64,
}

/// The times of `pipeline`'s row in the bench results `path`: the row whose file has the
/// pipeline's file name, on `scene` when given. Exactly one row must match (sweeps'
/// rows are left out); otherwise the error names the rows there are.
pub fn read(path: &Path, pipeline: &Path, scene: Option<&str>) -> Result<Timings, CommandError> {
    let shown = path.display();
    let text = read_text(path, MAX_BYTES)
        .map_err(|e| CommandError::Usage(format!("--timings {shown}: cannot read it: {e}")))?;
    let results: Results = serde_json::from_str(&text).map_err(|e| {
        // Exit 1, whose message main does not print: the file was read and is wrong.
        let message = format!("--timings {shown} is not a results.json of `rgraph bench`: {e}");
        eprintln!("error: {message}");
        CommandError::Invalid(message)
    })?;
    let file_name = pipeline.file_name();
    let of_file: Vec<&Row> = results
        .rows
        .iter()
        .filter(|r| r.sweep.is_none() && Path::new(&r.file).file_name() == file_name)
        .collect();
    let rows: Vec<&Row> = of_file
        .iter()
        .copied()
        .filter(|r| scene.is_none_or(|s| r.scene == s))
        .collect();
    let what = match scene {
        Some(scene) => format!("{} on {scene}", pipeline.display()),
        None => pipeline.display().to_string(),
    };
    let listed = |rows: &[&Row]| {
        rows.iter()
            .map(|r| format!("{} on {}", r.pipeline, r.scene))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let row = match rows.as_slice() {
        [row] => *row,
        [] if of_file.is_empty() => {
            let all: Vec<&Row> = results.rows.iter().filter(|r| r.sweep.is_none()).collect();
            return Err(CommandError::Usage(format!(
                "--timings {shown} has no row for {what}; its rows: {}",
                match all.is_empty() {
                    true => "none outside sweeps".to_owned(),
                    false => listed(&all),
                }
            )));
        }
        [] => {
            return Err(CommandError::Usage(format!(
                "--timings {shown} has no row for {what}; it has {}",
                listed(&of_file)
            )))
        }
        several => {
            return Err(CommandError::Usage(format!(
                "--timings {shown} has {} rows for {what}: {}; name the scene with --scene",
                several.len(),
                listed(several)
            )))
        }
    };
    let figures = match (&row.figures, row.status.as_str()) {
        (Some(figures), "ok") => figures,
        _ => {
            return Err(CommandError::Usage(format!(
                "--timings {shown}: the row for {} on {} measured nothing: {}",
                row.pipeline,
                row.scene,
                row.message.as_deref().unwrap_or("an error row")
            )))
        }
    };
    let [w, h] = results.resolution;
    Ok(Timings {
        source: format!(
            "{shown}: {} on {}, measured at {w}×{h} on {} (medians of the bench's rounds)",
            row.pipeline, row.scene, results.adapter.name
        ),
        gpu_frame_ms: figures.gpu_frame_ms.as_ref().map(|m| m.median),
        cpu_record_ms: figures.cpu_record_ms.as_ref().map(|m| m.median),
        passes: figures
            .passes
            .iter()
            .map(|p| PassTime {
                name: p.name.clone(),
                gpu_ms: p.gpu_ms.as_ref().map(|m| m.median),
                cpu_ms: p.cpu_ms.as_ref().map(|m| m.median),
            })
            .collect(),
    })
}
