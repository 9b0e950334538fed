//! results.md: the run's setting, then per scene one table a person reads (one row per
//! pipeline, error rows included) and the per-pass GPU times.

use std::fmt::Write;

use rgraph_core::explain::bytes;

use super::clocks::ClockSample;
use super::figures::{Figures, PassFigures};
use super::flag::Flag;
use super::images::slug;
use super::particle_table;
use super::plan_page;
use super::results::{Results, Row};
use super::rounds::RoundLog;
use super::specialisation::Specialisation;
use super::stats::Spread;

pub fn markdown(results: &Results) -> String {
    let mut md = String::new();
    let r = results;
    let _ = writeln!(md, "# rgraph bench\n");
    let _ = writeln!(md, "`{}`\n", r.command);
    let _ = writeln!(
        md,
        "- machine: {} ({}, {} cores)\n- adapter: {} [{} {}], {} {}\n- resolution: {}x{}; \
         each scene's pipelines timed together in {} interleaved rounds of {} frames each \
         after {} warmup frames{}; times are medians of the round medians\n- GPU clocks: \
         {}\n- commit: {}\n- time: {}, {:.0} s",
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
        r.rounds,
        r.frames,
        r.warmup,
        warmup_span(r.warmup),
        r.gpu_clocks.detail,
        r.git_commit,
        r.timestamp,
        r.elapsed_s,
    );
    if let Some(reference) = &r.reference {
        let spp = reference.spp.map_or("rendered as written".into(), |spp| {
            format!("{spp} shaded samples per pixel")
        });
        let _ = writeln!(
            md,
            "- reference: {} ({}, {spp})",
            reference.pipeline, reference.file
        );
    }
    for note in &r.notes {
        let _ = writeln!(md, "- note: {note}");
    }
    let mut scenes: Vec<&str> = r.rows.iter().map(|row| row.scene.as_str()).collect();
    scenes.dedup();
    for scene in scenes {
        let rows: Vec<&Row> = r.rows.iter().filter(|row| row.scene == scene).collect();
        let _ = writeln!(md, "\n## {scene}\n");
        if let Some(summary) = r.scenes.iter().find(|s| s.scene == scene) {
            if let Some(size) = &summary.size {
                let _ = writeln!(
                    md,
                    "{} triangles, {} meshes, {} lights; {:.1} MiB of vertices and indices \
                     uploaded.\n",
                    size.triangles,
                    size.meshes,
                    size.lights,
                    size.geometry_bytes as f64 / (1u64 << 20) as f64
                );
            }
            if let Some(edges) = &summary.edge_pixels {
                let share = edges.share * 100.0;
                let _ = writeln!(md, "Edge pixels: {share:.1}% ({}).\n", edges.definition);
            }
            if let Some(bound) = &summary.unique_surfaces {
                let _ = writeln!(
                    md,
                    "Lower bound at {}x: {:.3} shadings per pixel (one per distinct surface \
                     among a pixel's samples, from {}).\n",
                    bound.samples, bound.per_pixel, bound.graph
                );
            }
            if let Some(error) = &summary.unique_surfaces_error {
                let _ = writeln!(md, "Lower bound failed: {error}\n");
            }
            if let Some(error) = &summary.reference_error {
                let _ = writeln!(md, "Reference failed: {error}\n");
            }
        }
        md.push_str(&rounds_line(&r.round_log, scene, "results.json"));
        md.push_str(&scene_table(&rows));
        if r.scenes
            .iter()
            .any(|s| s.scene == scene && !s.images.is_empty())
        {
            md.push_str(&plan_links(scene, &rows));
        }
        let flags = rows
            .iter()
            .filter_map(|row| Some((name(row), row.figures.as_ref()?.flag.as_ref()?)));
        md.push_str(&flagged(flags, r.spread_limit));
        let passes: Vec<(String, &[PassFigures])> = rows
            .iter()
            .filter_map(|row| Some((name(row), &row.figures.as_ref()?.passes[..])))
            .collect();
        if !passes.is_empty() {
            md.push_str(&pass_table(passes));
        }
        md.push_str(&specialisation_table(&rows));
        md.push_str(&particle_table::per_scene(&rows));
    }
    md.push_str(&particle_table::by_extent(results));
    md.push_str(LEGEND);
    if r.sweep.is_none() {
        md.push_str(IMAGES);
    }
    md.push('\n');
    md
}

const HEADER: &str = "| pipeline | GPU ms | p10–p90 | spread | × noaa | CPU rec. ms | memory | \
                      pooled | G-buf B/sample | edge px | shaded/px | FLIP | edge FLIP | \
                      PSNR dB | edge PSNR dB |\n\
                      |---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|\n";
/// After a flagged row's GPU time.
pub const FLAG: &str = "⚑";

fn scene_table(rows: &[&Row]) -> String {
    let mut md = String::from(HEADER);
    for row in rows {
        let cells = match (&row.figures, &row.message) {
            (Some(f), _) => figure_cells(f),
            (None, message) => vec![error_cell(message.as_deref().unwrap_or("?"))],
        };
        let _ = writeln!(md, "| {} | {} |", name(row), cells.join(" | "));
    }
    md
}

/// Links to the measured rows' plan pages (plan_page.rs), in the scene's images folder.
fn plan_links(scene: &str, rows: &[&Row]) -> String {
    let links: Vec<String> = rows
        .iter()
        .filter(|row| row.figures.is_some())
        .map(|row| {
            let text = row.pipeline.replace('[', "\\[").replace(']', "\\]");
            let page = plan_page::file_name(&row.pipeline);
            format!("[{text}]({}/{page})", slug(scene))
        })
        .collect();
    match links.is_empty() {
        true => String::new(),
        false => format!("\nPlans with each pass's time: {}.\n", links.join(", ")),
    }
}

/// The GPU ms (flagged where `flagged`), p10–p90 and spread cells of a time measured in
/// rounds, "-" without one.
pub fn time_cells(gpu: Option<&Spread>, flagged: bool) -> [String; 3] {
    let flag = if flagged { FLAG } else { "" };
    [
        gpu.map_or("-".into(), |s| format!("{}{flag}", ms(s.median))),
        gpu.map_or("-".into(), |s| format!("{}–{}", ms(s.p10), ms(s.p90))),
        gpu.map_or("-".into(), |s| percent(s.spread)),
    ]
}

fn figure_cells(f: &Figures) -> Vec<String> {
    let mut cells = time_cells(f.gpu_frame_ms.as_ref(), f.flag.is_some()).to_vec();
    cells.extend([
        f.ratio_to_noaa.map_or("-".into(), |r| format!("{r:.2}")),
        f.cpu_record_ms
            .as_ref()
            .map_or("-".into(), |s| ms(s.median)),
        bytes(f.memory.total_bytes()),
        bytes(f.memory.allocated_bytes()),
        match (
            f.memory.gbuffer_stored_bytes_per_sample,
            f.memory.gbuffer_bytes_per_sample,
        ) {
            (Some(stored), Some(limit)) => format!("{stored} ({limit})"),
            _ => "-".into(),
        },
        f.work
            .edge_pixel_share
            .map_or("-".into(), |s| format!("{:.1}%", s * 100.0)),
        f.work
            .shaded_samples_per_pixel
            .map_or("-".into(), |s| format!("{s:.2}")),
    ]);
    let e = f.image_error.as_ref();
    cells.extend([
        e.map_or("-".into(), |e| format!("{:.4}", e.flip_mean)),
        e.and_then(|e| e.edge_flip_mean)
            .map_or("-".into(), |v| format!("{v:.4}")),
        e.map_or("-".into(), |e| psnr(e.psnr_db)),
        e.and_then(|e| e.edge_mse.map(|_| e.edge_psnr_db))
            .map_or("-".into(), psnr),
    ]);
    cells
}

/// How `scene`'s rounds ran: how many (`json`, the results file, logs them), in how many
/// memory groups, and the GPU's clocks over them where reported.
pub fn rounds_line(log: &[RoundLog], scene: &str, json: &str) -> String {
    let rounds: Vec<&RoundLog> = log.iter().filter(|l| l.scene == scene).collect();
    if rounds.is_empty() {
        return String::new();
    }
    let groups = rounds.iter().map(|l| l.group).max().unwrap_or(1);
    let plans = rounds.iter().map(|l| l.order.len()).max().unwrap_or(0);
    let mut line = format!(
        "Timed in {} rounds (round_log in {json}), up to {plans} plans a round",
        rounds.len()
    );
    if groups > 1 {
        let _ = write!(line, ", in {groups} groups that fit --group-memory");
    }
    let samples: Vec<&ClockSample> = rounds.iter().filter_map(|l| l.clocks.as_ref()).collect();
    let range = |values: Vec<u32>| {
        let (low, high) = (values.iter().min()?, values.iter().max()?);
        Some(match low == high {
            true => format!("{low}"),
            false => format!("{low}–{high}"),
        })
    };
    let sm = range(samples.iter().filter_map(|c| c.sm_mhz).collect());
    let mem = range(samples.iter().filter_map(|c| c.mem_mhz).collect());
    let temperature = range(samples.iter().filter_map(|c| c.temperature_c).collect());
    match (sm, mem, temperature) {
        (Some(sm), Some(mem), Some(temperature)) => {
            let mut reasons: Vec<&str> = samples
                .iter()
                .flat_map(|c| c.throttle.iter().copied())
                .filter(|t| *t != "gpu_idle")
                .collect();
            reasons.sort_unstable();
            reasons.dedup();
            let throttle = match reasons.is_empty() {
                true => "none but idle".to_string(),
                false => reasons.join(", "),
            };
            let _ = write!(
                line,
                ". GPU clocks in {} of them: SM {sm} MHz, memory {mem} MHz, {temperature} °C, \
                 throttle reasons: {throttle}",
                samples.len()
            );
        }
        _ => line.push_str(". GPU clocks: not reported"),
    }
    line.push_str(".\n\n");
    line
}

/// The flagged rows under a table, each named with its spread and reasons.
pub fn flagged<'a>(rows: impl IntoIterator<Item = (String, &'a Flag)>, limit: f64) -> String {
    let flagged: Vec<(String, &Flag)> = rows.into_iter().collect();
    if flagged.is_empty() {
        return String::new();
    }
    let mut md = format!(
        "\n{FLAG} Flagged: the round medians spread by more than {} of the time (p10–p90 \
         over the median); read these times as unmeasured until re-run:\n\n",
        percent(limit)
    );
    for (row, flag) in flagged {
        let reasons: Vec<&str> = flag.reasons.iter().map(|r| r.detail.as_str()).collect();
        let why = match reasons.is_empty() {
            true => "reason unknown".to_string(),
            false => reasons.join("; "),
        };
        let _ = writeln!(md, "- {row}: {}, {why}", percent(flag.spread));
    }
    md
}

/// What the warmup adds to its frames: a GPU at speed again (rounds.rs).
pub fn warmup_span(warmup: u32) -> &'static str {
    match warmup {
        0 => "",
        _ => " (for 0.5 s at least)",
    }
}

pub fn percent(share: f64) -> String {
    format!("{:.1}%", share * 100.0)
}

/// Identical images have no finite PSNR.
fn psnr(db: Option<f64>) -> String {
    db.map_or("∞".into(), |db| format!("{db:.1}"))
}

/// Median GPU ms of each pass, one line per named pipeline.
pub fn pass_table<'a>(rows: impl IntoIterator<Item = (String, &'a [PassFigures])>) -> String {
    let mut md = String::from("\n| pipeline | GPU ms per pass (median) |\n|---|---|\n");
    for (row, passes) in rows {
        let passes: Vec<String> = passes
            .iter()
            .map(|p| {
                let t = p.gpu_ms.as_ref().map_or("-".into(), |s| ms(s.median));
                format!("{} {t}", p.name)
            })
            .collect();
        let _ = writeln!(md, "| {row} | {} |", passes.join(", "));
    }
    md
}

/// What compiling for the scene's features saved, for the rows whose plans it changed;
/// nothing when it changed none.
fn specialisation_table(rows: &[&Row]) -> String {
    let special: Vec<(&Row, &Figures, &Specialisation)> = rows
        .iter()
        .filter_map(|row| {
            let f = row.figures.as_ref()?;
            Some((*row, f, f.specialisation.as_ref()?))
        })
        .collect();
    if special.is_empty() {
        return String::new();
    }
    let mut md = String::from(
        "\nSpecialised to the scene (the rows above) against the general plan. \
         \"by shaders\": the part of the GPU time saved that the shader variants save, \
         from the scene's plan timed with the general shaders too (\"-\" where only the \
         plan or only the shaders differ):\n\n\
         | pipeline | features | shader variants | passes | pooled memory | saved | GPU ms | \
         saved | by shaders |\n|---|---|---|--:|--:|--:|--:|--:|--:|\n",
    );
    for (row, f, s) in special {
        let (general, special) = (
            s.general_memory.allocated_bytes(),
            f.memory.allocated_bytes(),
        );
        let gpu = s
            .general_gpu_frame_ms
            .as_ref()
            .zip(f.gpu_frame_ms.as_ref())
            .map(|(g, f)| (g.median, f.median));
        let by_shaders = s
            .plan_only_gpu_frame_ms
            .as_ref()
            .zip(f.gpu_frame_ms.as_ref())
            .map_or("-".into(), |(p, f)| {
                format!("{} ms", ms(difference(p.median, f.median)))
            });
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} → {} | {} → {} | {} | {} | {} | {} |",
            name(row),
            s.features.join(", "),
            s.shader_variants.join(", "),
            s.general_passes,
            s.passes,
            bytes(general),
            bytes(special),
            share_saved(general as f64, special as f64),
            gpu.map_or("-".into(), |(g, f)| format!("{} → {}", ms(g), ms(f))),
            gpu.map_or("-".into(), |(g, f)| share_saved(g, f)),
            by_shaders,
        );
    }
    md
}

/// `a - b`, with differences that would print as "-0.00" printed as 0.
fn difference(a: f64, b: f64) -> f64 {
    let d = a - b;
    if d.abs() < 0.005 {
        0.0
    } else {
        d
    }
}

/// How much less `special` is than `general`, in percent of `general`.
fn share_saved(general: f64, special: f64) -> String {
    if general > 0.0 {
        format!("{:.0}%", (general - special) / general * 100.0)
    } else {
        "-".into()
    }
}

/// An error's first line (compile errors list every texture at fault; the JSON has all).
fn error_cell(message: &str) -> String {
    let mut lines = message.lines();
    let first = lines.next().unwrap_or("").replace('|', "\\|");
    match lines.count() {
        0 => format!("error: {first}"),
        more => format!("error: {first} (+{more} more in results.json)"),
    }
}

/// The pipeline, with the sweep value in a sweep.
fn name(row: &Row) -> String {
    match &row.sweep {
        Some(point) => format!("{} ({})", row.pipeline, point.label),
        None => row.pipeline.clone(),
    }
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
GPU ms: GPU frame time from timestamps (first pass's begin to last pass's end). A scene's \
pipelines take turns in interleaved rounds (A B C, A B C, ...), each running its frames of \
the round; a row's time is the median of its round medians (each round's median over its \
frames). p10–p90: the 10th and 90th percentiles of the round medians by nearest rank (with 9 \
rounds or fewer, the fastest and the slowest round); spread: (p90 − p10) / median. A row \
whose spread exceeds 5% is flagged (⚑) and listed under its table with the reasons the bench \
knows: a first-use compile (pipelines created inside measured frames), GPU clocks that \
changed between its rounds, a thermal slowdown or power cap reported in a round, or one \
outlier round without which the others agree. GPU clocks are sampled once per round where \
the platform reports them (nvidia-smi on NVIDIA; not on lavapipe). × noaa: the time over \
deferred_noaa's on the same scene (and sweep value) in this run. CPU rec.: CPU time to record \
all passes, the median of round medians too. memory / pooled: \
bytes of the graph's textures and buffers on their own and after sharing, each with the \
buffers passes keep for themselves (a compute rasteriser's bins, a list of edge pixels; \
results.json's pass_bytes). G-buf B/sample: what one \
sample of the gbuffer pass's targets occupies, depth-stencil included (D32S8 as 8 bytes); in \
brackets its color targets as WebGPU's limit on them counts (each aligned to its component size). edge px: pixels the pipeline's debug.edges \
marks; shaded/px: shading invocations per pixel (edge pixels once per sample, others once; \
pipelines without debug.edges by their kind, see results.json). On lavapipe times are CPU \
rasterisation: compare ratios within one run only. FLIP: mean of NVIDIA's FLIP error \
(0 = identical, 1 = maximal) against the reference on the tone-mapped 8-bit images; PSNR \
on the sRGB channels; edge: both restricted to the scene's edge pixels. Every pipeline is \
compiled for its scene's features (rgraph explain --scene shows what that drops); where that \
changes the plan, the general plan is timed too and a table per scene shows what was saved. \
Particle pipelines (seed 001): particle Mpx are the fragments their particle passes shade \
(billboard pixels, overlaps counted), image-processing Mpx those of the depth downsample, \
edge detection and composite, both counted on the CPU (results.json says how the \
stencilled full-resolution pass of mixed resolution is estimated); particle GPU ms: the \
median GPU times of those passes added up, the technique's cost apart from the opaque \
frame; saved: that against particles_full_res's on the same scene.";

/// Outside sweeps, which write no images.
const IMAGES: &str = " Images per scene are in the folder next to this file: reference.png, \
edge_pixels.png, PIPELINE.png, PIPELINE_error.png (FLIP heat map), PIPELINE_edges.png \
(debug.edges), and PIPELINE.plan.html, the timed plan as a page (`rgraph explain --format html`).";
