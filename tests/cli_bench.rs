//! `rgraph bench` as a user runs it: the built binary on lavapipe (unless RGRAPH_ADAPTER
//! says otherwise) at 64x48 with one frame a round, three rounds and no warmup, checked
//! through its exit status, results.json, and the charts and images it writes. A machine
//! without a Vulkan adapter fails these tests with the binary's own explanation: they
//! never skip.

use crate::cli_support;

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use cli_support::{rgraph, Run};
use serde_json::Value;
use tempfile::TempDir;

const NOAA: &str = "pipelines/deferred_noaa.ron";
const PER_SAMPLE: &str = "pipelines/deferred_per_sample_4x.ron";
const REFERENCE: &str = "pipelines/reference_ssaa16.ron";
const MISSING: &str = "pipelines/no_such_pipeline.ron";

/// Rounds of every run here but the stopped one's.
const ROUNDS: usize = 3;

fn bench(args: &[&str]) -> Run {
    let size = [
        "bench", "--width", "64", "--height", "48", "--frames", "1", "--rounds", "3", "--warmup",
        "0",
    ];
    rgraph(&[&size[..], args].concat())
}

/// The main run, shared by the tests that read it: builtin:dense with no-AA, per-sample
/// shading, the reference itself, and a pipeline file that does not exist.
struct Bench {
    dir: TempDir,
    json: Value,
}

fn main_run() -> &'static Bench {
    static RUN: OnceLock<Bench> = OnceLock::new();
    RUN.get_or_init(|| {
        let dir = tempfile::tempdir().expect("a temporary directory");
        let out = dir
            .path()
            .to_str()
            .expect("temp paths are UTF-8")
            .to_string();
        let run = bench(&[
            "--scene",
            "builtin:dense",
            "--pipeline",
            NOAA,
            "--pipeline",
            PER_SAMPLE,
            "--pipeline",
            REFERENCE,
            "--pipeline",
            MISSING,
            "--out-dir",
            &out,
        ])
        .expect(0);
        let json_path = dir.path().join("results.json");
        assert_eq!(run.stdout.trim(), json_path.display().to_string());
        let json = read_json(&json_path);
        Bench { dir, json }
    })
}

fn read_json(path: &Path) -> Value {
    let text = std::fs::read_to_string(path)
        .unwrap_or_else(|e| panic!("{} is not readable: {e}", path.display()));
    serde_json::from_str(&text).unwrap_or_else(|e| panic!("{} is not JSON: {e}", path.display()))
}

/// The row of `pipeline` (a file stem).
fn row<'a>(json: &'a Value, pipeline: &str) -> &'a Value {
    json["rows"]
        .as_array()
        .expect("rows is an array")
        .iter()
        .find(|r| r["pipeline"] == pipeline)
        .unwrap_or_else(|| panic!("no row for {pipeline} in {json:#}"))
}

fn number(value: &Value, path: &str) -> f64 {
    let field = path.split('.').fold(value, |v, key| &v[key]);
    field
        .as_f64()
        .unwrap_or_else(|| panic!("{path} is not a number: {field} in {value:#}"))
}

/// Checks that every key of `keys` is present in `value` and of the kind named.
fn assert_fields(value: &Value, keys: &[(&str, &str)]) {
    for (key, kind) in keys {
        let field = value
            .get(key)
            .unwrap_or_else(|| panic!("missing field {key} in {value:#}"));
        let ok = match *kind {
            "string" => field.is_string(),
            "number" => field.is_number(),
            "array" => field.is_array(),
            "object" => field.is_object(),
            "spread" => {
                ["median", "p10", "p90", "min", "max", "spread"]
                    .iter()
                    .all(|k| field[k].is_number())
                    && field["rounds"]
                        .as_array()
                        .is_some_and(|r| r.len() == ROUNDS)
            }
            "number|null" => field.is_number() || field.is_null(),
            "string|null" => field.is_string() || field.is_null(),
            "object|null" => field.is_object() || field.is_null(),
            other => panic!("unknown kind {other}"),
        };
        assert!(ok, "field {key} should be {kind}, is {field}");
    }
}

#[test]
fn results_json_has_every_figure_with_its_type() {
    let json = &main_run().json;
    assert_fields(
        json,
        &[
            ("schema", "number"),
            ("command", "string"),
            ("machine", "object"),
            ("adapter", "object"),
            ("git_commit", "string"),
            ("timestamp", "string"),
            ("elapsed_s", "number"),
            ("resolution", "array"),
            ("frames", "number"),
            ("rounds", "number"),
            ("warmup", "number"),
            ("spread_limit", "number"),
            ("group_memory_bytes", "number"),
            ("gpu_clocks", "object"),
            ("reference", "object"),
            ("notes", "array"),
            ("scenes", "array"),
            ("rows", "array"),
            ("round_log", "array"),
        ],
    );
    assert_eq!((&json["frames"], &json["rounds"]), (&1.into(), &3.into()));
    assert_eq!(json["spread_limit"], 0.05);
    assert_eq!(json["resolution"], serde_json::json!([64, 48]));
    assert_fields(
        &json["machine"],
        &[
            ("hostname", "string"),
            ("cpu", "string"),
            ("cpu_cores", "number"),
        ],
    );
    assert_fields(
        &json["adapter"],
        &[
            ("name", "string"),
            ("driver", "string"),
            ("driver_info", "string"),
            ("backend", "string"),
            ("device_type", "string"),
        ],
    );
    let timestamp = json["timestamp"].as_str().unwrap();
    assert!(
        timestamp.len() == 20 && timestamp.ends_with('Z') && timestamp.contains('T'),
        "{timestamp}"
    );
    assert_eq!(json["reference"]["spp"], 16);
    assert_fields(
        &json["scenes"][0]["edge_pixels"],
        &[("share", "number"), ("definition", "string")],
    );

    let noaa = row(json, "deferred_noaa");
    assert_eq!(noaa["status"], "ok");
    let figures = &noaa["figures"];
    assert_fields(
        figures,
        &[
            ("samples", "number"),
            ("gpu_frame_ms", "spread"),
            ("flag", "object|null"),
            ("created_while_measured", "array"),
            ("cpu_record_ms", "spread"),
            ("ratio_to_noaa", "number"),
            ("passes", "array"),
            ("memory", "object"),
            ("work", "object"),
            ("image_error", "object"),
            ("specialisation", "object|null"),
            ("particles", "object|null"),
        ],
    );
    assert!(
        figures["particles"].is_null(),
        "no particle passes: {figures:#}"
    );
    assert_eq!(number(figures, "ratio_to_noaa"), 1.0);
    for pass in figures["passes"].as_array().unwrap() {
        assert_fields(
            pass,
            &[
                ("name", "string"),
                ("kind", "string"),
                ("gpu_ms", "spread"),
                ("cpu_ms", "spread"),
            ],
        );
    }
    assert_fields(
        &figures["memory"],
        &[
            ("logical_bytes", "number"),
            ("physical_bytes", "number"),
            ("pass_bytes", "number"),
            ("gbuffer_bytes_per_sample", "number"),
            ("gbuffer_stored_bytes_per_sample", "number"),
        ],
    );
    assert!(number(figures, "memory.physical_bytes") > 0.0);
    // A G-buffer pipeline's passes keep no buffers of their own.
    assert_eq!(number(figures, "memory.pass_bytes"), 0.0);
    assert_fields(
        &figures["work"],
        &[
            ("edge_pixel_share", "number"),
            ("shaded_samples_per_pixel", "number"),
            ("source", "string"),
            ("unique_surface_bound", "number|null"),
        ],
    );
    assert_fields(
        &figures["image_error"],
        &[
            ("flip_mean", "number"),
            ("mse", "number"),
            ("psnr_db", "number|null"),
            ("edge_flip_mean", "number|null"),
            ("edge_mse", "number|null"),
            ("edge_psnr_db", "number|null"),
        ],
    );
}

#[test]
fn the_reference_against_itself_has_no_error() {
    let error = &row(&main_run().json, "reference_ssaa16")["figures"]["image_error"];
    assert_eq!(number(error, "flip_mean"), 0.0, "{error:#}");
    assert_eq!(number(error, "mse"), 0.0, "{error:#}");
    assert!(error["psnr_db"].is_null(), "identical images: {error:#}");
}

#[test]
fn per_sample_shading_has_no_more_error_than_no_aa() {
    let json = &main_run().json;
    let noaa = &row(json, "deferred_noaa")["figures"];
    let per_sample = &row(json, "deferred_per_sample_4x")["figures"];
    for figure in [
        "image_error.flip_mean",
        "image_error.edge_flip_mean",
        "image_error.mse",
    ] {
        let (ps, na) = (number(per_sample, figure), number(noaa, figure));
        assert!(ps <= na, "{figure}: per-sample {ps} > no-AA {na}");
    }
    // Per-sample shading shades every sample; no-AA once per pixel.
    assert_eq!(number(per_sample, "work.shaded_samples_per_pixel"), 4.0);
    assert_eq!(number(noaa, "work.shaded_samples_per_pixel"), 1.0);
}

#[test]
fn the_unique_surface_bound_lies_between_one_and_the_sample_count() {
    let json = &main_run().json;
    let bound = number(&json["scenes"][0], "unique_surfaces.per_pixel");
    // builtin:dense has many edges: more than one surface in some pixels.
    assert!(bound > 1.0 && bound < 4.0, "{bound}");
    let per_sample = &row(json, "deferred_per_sample_4x")["figures"];
    assert_eq!(number(per_sample, "work.unique_surface_bound"), bound);
    // Counted at 4x: no bound for a 1-sample pipeline.
    assert!(row(json, "deferred_noaa")["figures"]["work"]["unique_surface_bound"].is_null());
}

#[test]
fn an_unknown_pipeline_is_an_error_row_and_the_rest_are_measured() {
    let json = &main_run().json;
    let missing = row(json, "no_such_pipeline");
    assert_eq!(missing["status"], "error");
    assert!(missing["figures"].is_null());
    let message = missing["message"].as_str().unwrap();
    assert!(
        message.contains(MISSING) && message.contains("builtin:dense"),
        "{message}"
    );
    let measured = json["rows"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|r| r["status"] == "ok");
    assert_eq!(measured.count(), 3);
}

#[test]
fn charts_images_plan_pages_and_the_table_are_written() {
    let dir = main_run().dir.path();
    let scene = dir.join("builtin_dense");
    let pngs: Vec<PathBuf> = [
        dir.join("pareto.png"),
        dir.join("passes.png"),
        scene.join("reference.png"),
        scene.join("edge_pixels.png"),
        scene.join("deferred_noaa.png"),
        scene.join("deferred_noaa_error.png"),
        scene.join("deferred_noaa_edges.png"),
        scene.join("deferred_per_sample_4x_error.png"),
    ]
    .into();
    for png in &pngs {
        let image = image::open(png)
            .unwrap_or_else(|e| panic!("{} is not a readable PNG: {e}", png.display()));
        assert!(image.width() > 0 && image.height() > 0);
    }
    let reference = image::open(scene.join("reference.png")).unwrap();
    assert_eq!((reference.width(), reference.height()), (64, 48));
    let table = std::fs::read_to_string(dir.join("results.md")).unwrap();
    assert!(table.contains("| deferred_per_sample_4x |"), "{table}");
    assert!(table.contains("| no_such_pipeline | error:"), "{table}");
    // Each measured pipeline's plan as a page beside its images, with its times, linked
    // from the table.
    let page = std::fs::read_to_string(scene.join("deferred_noaa.plan.html"))
        .expect("deferred_noaa's plan page beside its images");
    assert!(
        page.starts_with("<!DOCTYPE html>"),
        "{}",
        &page[..page.len().min(200)]
    );
    assert!(page.contains("GPU ms"), "the page shows the measured times");
    assert!(
        table.contains("(builtin_dense/deferred_noaa.plan.html)"),
        "{table}"
    );
}

#[test]
fn nothing_measurable_exits_1_and_still_writes_the_error_rows() {
    let dir = tempfile::tempdir().unwrap();
    let run = bench(&[
        "--scene",
        "builtin:no_such_scene",
        "--pipeline",
        NOAA,
        "--out-dir",
        dir.path().to_str().unwrap(),
    ])
    .expect(1);
    assert!(
        run.stderr.contains("nothing could be measured"),
        "{}",
        run.stderr
    );
    let json = read_json(&dir.path().join("results.json"));
    let rows = json["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 1);
    assert_eq!(rows[0]["status"], "error");
    let message = rows[0]["message"].as_str().unwrap();
    assert!(
        message.contains("unknown built-in scene `no_such_scene`"),
        "{message}"
    );
}

#[test]
fn a_sample_count_the_device_lacks_is_an_error_row_of_the_sweep() {
    let dir = tempfile::tempdir().unwrap();
    bench(&[
        "--sweep",
        "samples",
        "--scene",
        "builtin:unlit",
        "--pipeline",
        NOAA,
        "--pipeline",
        "pipelines/forward_msaa_4x.ron",
        "--out-dir",
        dir.path().to_str().unwrap(),
    ])
    .expect(0);
    let json = read_json(&dir.path().join("results.json"));
    assert_eq!(json["sweep"], "samples");
    let rows = json["rows"].as_array().unwrap();
    assert_eq!(
        rows.len(),
        8,
        "one row per pipeline and sample count: {json:#}"
    );
    let forward = |value: u32| {
        rows.iter()
            .find(|r| r["pipeline"] == "forward_msaa_4x" && r["sweep"]["value"] == value)
            .unwrap()
    };
    assert_eq!(forward(4)["status"], "ok", "{:#}", forward(4));
    // Ratios pair rows of the same sweep value: the baseline's is 1 at every value.
    for row in rows.iter().filter(|r| r["pipeline"] == "deferred_noaa") {
        assert_eq!(number(&row["figures"], "ratio_to_noaa"), 1.0, "{row:#}");
    }
    // lavapipe has 1x and 4x only; a device with 2x and 8x measures those too.
    for row in rows.iter().filter(|r| r["status"] == "error") {
        let message = row["message"].as_str().unwrap();
        assert!(message.contains("multisampling"), "{message}");
    }
    assert!(dir.path().join("scaling.png").is_file());
}

/// A sweep over a built-in scene's size: one step per value up to --sweep-max, each
/// scene's size in results.json and results.md, and the cost chart.
#[test]
fn the_mesh_sweep_stops_at_sweep_max_and_records_each_scene_size() {
    let dir = tempfile::tempdir().unwrap();
    bench(&[
        "--sweep",
        "meshes",
        "--sweep-max",
        "10",
        "--pipeline",
        "pipelines/forward_msaa_4x.ron",
        "--out-dir",
        dir.path().to_str().unwrap(),
    ])
    .expect(0);
    let json = read_json(&dir.path().join("results.json"));
    let rows = json["rows"].as_array().unwrap();
    let labels: Vec<&str> = rows
        .iter()
        .map(|r| r["sweep"]["label"].as_str().unwrap())
        .collect();
    assert_eq!(labels, ["2 meshes", "10 meshes"], "{json:#}");
    let scenes: Vec<(&str, u64)> = json["scenes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| {
            (
                s["scene"].as_str().unwrap(),
                s["size"]["meshes"].as_u64().unwrap(),
            )
        })
        .collect();
    assert_eq!(
        scenes,
        [("builtin:city?blocks=1", 2), ("builtin:city?blocks=3", 10)]
    );
    // The ground (4 vertices, 6 indices) and 9 buildings (24 and 36 each) of 56 and 4 bytes.
    let bytes = json["scenes"][1]["size"]["geometry_bytes"]
        .as_u64()
        .unwrap();
    assert_eq!(bytes, (4 + 9 * 24) * 56 + (6 + 9 * 36) * 4);
    let md = std::fs::read_to_string(dir.path().join("results.md")).unwrap();
    assert!(md.contains("110 triangles, 10 meshes, 5 lights"), "{md}");
    assert!(dir.path().join("scaling.png").is_file());
}

#[test]
fn a_specialised_plan_is_measured_beside_the_general_one() {
    let dir = tempfile::tempdir().unwrap();
    bench(&[
        "--scene",
        "builtin:unlit",
        "--pipeline",
        NOAA,
        "--no-reference",
        "--out-dir",
        dir.path().to_str().unwrap(),
    ])
    .expect(0);
    let json = read_json(&dir.path().join("results.json"));
    let figures = &row(&json, "deferred_noaa")["figures"];
    let special = &figures["specialisation"];
    assert_fields(
        special,
        &[
            ("features", "array"),
            ("shader_variants", "array"),
            ("passes", "number"),
            ("general_passes", "number"),
            ("general_memory", "object"),
            ("general_gpu_frame_ms", "spread"),
            // Both the plan and the shaders differ, so the plan is timed with each.
            ("plan_only_gpu_frame_ms", "spread"),
        ],
    );
    assert!(
        special["features"]
            .as_array()
            .unwrap()
            .contains(&"unlit_only".into()),
        "{special:#}"
    );
    // The unlit G-buffer pass and the tone mapping, instead of the shadow maps, the light
    // and the transparent and points and lines passes too.
    assert_eq!(
        (number(special, "passes"), number(special, "general_passes")),
        (2.0, 8.0)
    );
    assert_eq!(figures["passes"].as_array().unwrap().len(), 2);
    // Normal and material (4 bytes each) and the transparent accumulation (rgba16float, 8;
    // the points and lines' shares its memory in the general plan) are not allocated at 64x48, and the depth-stencil is depth24plus-stencil8 (4 bytes)
    // instead of depth32float-stencil8 (8, padded); nor is the 4096 x 4096 depth32float
    // shadow atlas; nor are the material layers' targets the general plan stores on
    // lavapipe (specular and sheen 4 bytes, the coat 8: 8 after pooling).
    assert_eq!(
        number(special, "general_memory.physical_bytes") - number(figures, "memory.physical_bytes"),
        64.0 * 48.0 * (4.0 + 4.0 + 4.0 + 8.0 + 8.0) + 4096.0 * 4096.0 * 4.0
    );
    assert_eq!(number(figures, "memory.gbuffer_bytes_per_sample"), 20.0);
    // albedo 4, view depth 4, HDR 8 and the depth-stencil 4.
    assert_eq!(
        number(figures, "memory.gbuffer_stored_bytes_per_sample"),
        20.0
    );
    let table = std::fs::read_to_string(dir.path().join("results.md")).unwrap();
    assert!(
        table.contains("| deferred_noaa | color_bytes_64, no_lights, shallow_depth, unlit_only | gbuffer.wgsl {double_sided} | 8 → 2 |"),
        "{table}"
    );
    let row = table
        .lines()
        .find(|l| l.starts_with("| deferred_noaa | color_bytes_64, no_lights"))
        .unwrap();
    assert!(row.ends_with(" ms |"), "no time saved by shaders: {row}");
}

/// A file that drops its edge view for a scene (deferred_msaa_4x_tiled has none on an
/// unlit-only scene: nothing is lit, so nothing is split) is measured all the same, its
/// row saying why it has no edge figures.
#[test]
fn an_edge_view_the_scene_drops_leaves_the_row_without_edge_figures() {
    let dir = tempfile::tempdir().unwrap();
    bench(&[
        "--scene",
        "builtin:unlit",
        "--pipeline",
        "pipelines/deferred_msaa_4x_tiled.ron",
        "--no-reference",
        "--out-dir",
        dir.path().to_str().unwrap(),
    ])
    .expect(0);
    let json = read_json(&dir.path().join("results.json"));
    let figures = &row(&json, "deferred_msaa_4x_tiled")["figures"];
    assert!(number(figures, "gpu_frame_ms.median") > 0.0, "{figures:#}");
    let work = &figures["work"];
    assert!(work["edge_pixel_share"].is_null(), "{work:#}");
    assert_eq!(
        work["source"],
        "not counted: debug.edges is not made for this scene (condition \"!unlit_only\" is false)"
    );
}

/// A run stopped part way keeps what it measured: after each scene results.json and
/// results.md hold the rows so far, with a note saying how many scenes are missing (the
/// second scene here, a thousand lights shaded per sample, takes seconds on lavapipe,
/// and the run is killed as soon as the first scene's results.md appears, which is
/// written after results.json).
#[test]
fn a_run_stopped_after_one_scene_keeps_its_rows() {
    let dir = TempDir::new().unwrap();
    let out = dir.path().to_str().unwrap();
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_rgraph"))
        .args([
            "bench",
            "--pipeline",
            PER_SAMPLE,
            "--scene",
            "builtin:spheres",
            "--scene",
            "builtin:lights?count=1024",
            "--no-reference",
            "--width",
            "320",
            "--height",
            "180",
            "--frames",
            "3",
            "--warmup",
            "1",
            "--out-dir",
            out,
        ])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .expect("the rgraph binary runs");
    let (json, table) = (
        dir.path().join("results.json"),
        dir.path().join("results.md"),
    );
    while !table.exists() {
        if let Some(status) = child.try_wait().unwrap() {
            panic!("rgraph bench ended ({status}) before writing any results");
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    child.kill().unwrap();
    child.wait().unwrap();
    let results: Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let rows = results["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 1, "{rows:?}");
    assert_eq!(rows[0]["scene"], "builtin:spheres");
    let notes = results["notes"].to_string();
    assert!(notes.contains("partial: 1 of 2 scenes measured"), "{notes}");
    let table = std::fs::read_to_string(table).unwrap();
    assert!(table.contains("partial: 1 of 2 scenes measured"), "{table}");
}

/// The names of the plans each round ran, in order, for `scene`.
fn round_orders(json: &Value, scene: &str) -> Vec<(u64, u64, Vec<String>)> {
    json["round_log"]
        .as_array()
        .expect("round_log is an array")
        .iter()
        .filter(|r| r["scene"] == scene)
        .map(|r| {
            let order = r["order"].as_array().unwrap();
            let names = order.iter().map(|n| n.as_str().unwrap().to_string());
            (
                r["group"].as_u64().unwrap(),
                r["round"].as_u64().unwrap(),
                names.collect(),
            )
        })
        .collect()
}

/// Every measured plan of the run's rows, in the order the rows were given: each row's
/// plan, then its general plan and its plan with the general shaders where timed.
fn timed_plans(json: &Value) -> Vec<String> {
    let mut plans = Vec::new();
    for row in json["rows"].as_array().unwrap() {
        let Some(figures) = row["figures"].as_object() else {
            continue;
        };
        let name = row["pipeline"].as_str().unwrap();
        plans.push(name.to_string());
        let special = &figures["specialisation"];
        if !special.is_null() {
            plans.push(format!("{name} (general)"));
            if !special["plan_only_gpu_frame_ms"].is_null() {
                plans.push(format!("{name} (plan only)"));
            }
        }
    }
    plans
}

#[test]
fn pipelines_take_turns_in_every_round() {
    let json = &main_run().json;
    let plans = timed_plans(json);
    assert!(plans.len() >= 3, "{plans:?}");
    // A B C, A B C, A B C: every plan once a round, in the order given, in one group.
    let expected: Vec<(u64, u64, Vec<String>)> = (1..=ROUNDS as u64)
        .map(|round| (1, round, plans.clone()))
        .collect();
    assert_eq!(round_orders(json, "builtin:dense"), expected);
    // The row's time comes from those rounds: one median per round.
    let noaa = &row(json, "deferred_noaa")["figures"]["gpu_frame_ms"];
    let medians: Vec<f64> = noaa["rounds"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    let mut sorted = medians.clone();
    sorted.sort_by(f64::total_cmp);
    assert_eq!(number(noaa, "median"), sorted[1], "{noaa:#}");
    assert_eq!(
        (number(noaa, "p10"), number(noaa, "p90")),
        (sorted[0], sorted[2])
    );
}

#[test]
fn lavapipe_reports_no_clocks_and_a_first_use_compile_is_recorded() {
    let json = &main_run().json;
    let clocks = &json["gpu_clocks"];
    assert!(clocks["reported_by"].is_null(), "{clocks:#}");
    let detail = clocks["detail"].as_str().unwrap();
    assert!(detail.starts_with("not reported: "), "{detail}");
    assert!(json["round_log"]
        .as_array()
        .unwrap()
        .iter()
        .all(|r| r["clocks"].is_null()));
    let table = std::fs::read_to_string(main_run().dir.path().join("results.md")).unwrap();
    assert!(table.contains("GPU clocks: not reported"), "{table}");
    // Without warmup the first round's frames create the pipelines, and only they do: a
    // pipeline is built once a device (passes/src/kept.rs), so by the first row to need
    // it, which need not be deferred_noaa's.
    let rows = json["rows"].as_array().unwrap();
    let created: Vec<&Value> = (rows.iter())
        .filter_map(|r| r["figures"]["created_while_measured"].as_array())
        .flatten()
        .collect();
    assert!(
        !created.is_empty(),
        "no row created a pipeline while measured"
    );
    assert!(created.iter().all(|c| c["round"] == 1), "{created:?}");
    assert!(
        created.iter().any(|c| number(c, "render_pipelines") > 0.0),
        "{created:?}"
    );
    // A row flagged where it compiled has the compile among its reasons.
    for r in rows {
        let figures = &r["figures"];
        let compiled = figures["created_while_measured"]
            .as_array()
            .is_some_and(|c| !c.is_empty());
        if let (true, Some(flag)) = (compiled, figures["flag"].as_object()) {
            let kinds = flag["reasons"].as_array().unwrap();
            assert!(
                kinds.iter().any(|r| r["kind"] == "first_use_compile"),
                "{flag:?}"
            );
        }
    }
}

#[test]
fn warmup_frames_keep_pipeline_creation_out_of_the_rounds() {
    let dir = tempfile::tempdir().unwrap();
    rgraph(&[
        "bench",
        "--width",
        "64",
        "--height",
        "48",
        "--frames",
        "1",
        "--rounds",
        "2",
        "--warmup",
        "1",
        "--scene",
        "builtin:unlit",
        "--pipeline",
        NOAA,
        "--no-reference",
        "--out-dir",
        dir.path().to_str().unwrap(),
    ])
    .expect(0);
    let json = read_json(&dir.path().join("results.json"));
    let figures = &row(&json, "deferred_noaa")["figures"];
    assert_eq!(figures["created_while_measured"], serde_json::json!([]));
    assert_eq!(number(&json, "warmup"), 1.0);
}

/// A round made slow through the bench's test hook (its GPU times ten times as long)
/// flags every row it slowed, in results.json and results.md, and the notes say that
/// the figures were changed.
#[test]
fn a_fake_slow_round_is_flagged() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().to_str().unwrap();
    let run = std::process::Command::new(env!("CARGO_BIN_EXE_rgraph"))
        .args([
            "bench",
            "--width",
            "64",
            "--height",
            "48",
            "--frames",
            "3",
            "--rounds",
            "5",
            "--warmup",
            "1",
            "--scene",
            "builtin:unlit",
            "--pipeline",
            NOAA,
            "--no-reference",
            "--out-dir",
            out,
        ])
        .env("RGRAPH_BENCH_FAKE_SLOW_ROUND", "2")
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("the rgraph binary runs");
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let json = read_json(&dir.path().join("results.json"));
    let notes = json["notes"].to_string();
    assert!(notes.contains("RGRAPH_BENCH_FAKE_SLOW_ROUND=2"), "{notes}");
    let figures = &row(&json, "deferred_noaa")["figures"];
    let time = &figures["gpu_frame_ms"];
    let rounds: Vec<f64> = time["rounds"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    // Round 2 is the slowest by far: ten times as long as its real frames.
    let slowest = (0..rounds.len()).max_by(|a, b| rounds[*a].total_cmp(&rounds[*b]));
    assert_eq!(slowest, Some(1), "{rounds:?}");
    let flag = &figures["flag"];
    assert!(
        flag.is_object(),
        "a slow round must flag the row: {figures:#}"
    );
    assert_eq!(flag["spread"], time["spread"]);
    assert!(number(flag, "spread") > 0.05, "{flag:#}");
    // When the other rounds agree, the reason names round 2 and no other.
    for reason in flag["reasons"].as_array().unwrap() {
        if reason["kind"] == "outlier_round" {
            let detail = reason["detail"].as_str().unwrap();
            assert!(
                detail.starts_with("a slow outlier round: round 2 "),
                "{detail}"
            );
        }
    }
    let table = std::fs::read_to_string(dir.path().join("results.md")).unwrap();
    assert!(table.contains("⚑ Flagged"), "{table}");
    assert!(table.contains("\n- deferred_noaa: "), "{table}");
    let line = table
        .lines()
        .find(|l| l.starts_with("| deferred_noaa |"))
        .unwrap();
    assert!(line.contains('⚑'), "{line}");
}

/// With a memory budget smaller than any one plan, each plan is timed in a group of its
/// own, every group in its own rounds.
#[test]
fn a_memory_budget_splits_the_rounds_into_groups() {
    let dir = tempfile::tempdir().unwrap();
    rgraph(&[
        "bench",
        "--width",
        "320",
        "--height",
        "240",
        "--frames",
        "1",
        "--rounds",
        "2",
        "--warmup",
        "0",
        "--group-memory",
        "1",
        "--scene",
        "builtin:unlit",
        "--pipeline",
        NOAA,
        "--pipeline",
        PER_SAMPLE,
        "--no-reference",
        "--out-dir",
        dir.path().to_str().unwrap(),
    ])
    .expect(0);
    let json = read_json(&dir.path().join("results.json"));
    assert_eq!(number(&json, "group_memory_bytes"), f64::from(1 << 20));
    let plans = timed_plans(&json);
    let expected: Vec<(u64, u64, Vec<String>)> = plans
        .iter()
        .enumerate()
        .flat_map(|(i, plan)| (1..=2).map(move |round| (i as u64 + 1, round, vec![plan.clone()])))
        .collect();
    assert_eq!(round_orders(&json, "builtin:unlit"), expected);
    let table = std::fs::read_to_string(dir.path().join("results.md")).unwrap();
    let groups = format!("in {} groups that fit --group-memory", plans.len());
    assert!(table.contains(&groups), "{table}");
}

/// The pass names of `pipeline`'s row.
fn pass_names(json: &Value, pipeline: &str) -> Vec<String> {
    let passes = row(json, pipeline)["figures"]["passes"].as_array().unwrap();
    (passes.iter())
        .map(|p| p["name"].as_str().unwrap().to_string())
        .collect()
}

/// `--shadows` and `--shadowed-lights` set the scene's shadows as `render` does: off drops
/// the shadow passes from the measured plan, and the notes say what was measured: among
/// it, maps drawn every frame (the bench's frames are still, which would keep them).
#[test]
fn bench_takes_the_shadow_settings_of_render() {
    let run = |shadows: &[&str]| {
        let dir = tempfile::tempdir().unwrap();
        let args = [
            &["--scene", "builtin:spheres", "--no-reference"][..],
            shadows,
            &["--out-dir", dir.path().to_str().unwrap()],
        ];
        bench(&args.concat()).expect(0);
        read_json(&dir.path().join("results.json"))
    };
    let pipeline = "visibility_msaa_4x";
    let shadowed = run(&["--pipeline", "pipelines/visibility_msaa_4x.ron"]);
    assert!(
        pass_names(&shadowed, pipeline).contains(&"shadow maps".to_string()),
        "{:?}",
        pass_names(&shadowed, pipeline)
    );
    let notes = shadowed["notes"].to_string();
    assert!(!notes.contains("shadows:"), "{notes}");
    assert!(
        notes.contains(
            "shadow maps drawn every frame (shadow_cache=0 for pipelines/visibility_msaa_4x.ron)"
        ),
        "{notes}"
    );
    let off = run(&[
        "--pipeline",
        "pipelines/visibility_msaa_4x.ron",
        "--shadows",
        "off",
    ]);
    let names = pass_names(&off, pipeline);
    assert!(!names.iter().any(|n| n.contains("shadow")), "{names:?}");
    let notes = off["notes"].to_string();
    assert!(
        notes.contains("shadows: off, at most 4 shadowed lights"),
        "{notes}"
    );
    bench(&["--shadowed-lights", "65", "--out-dir", "unused"])
        .expect(2)
        .stderr_has("65 shadowed lights is out of range: at most 64");
}

/// `--param shadow_map=512,2048` measures each pipeline declaring the parameter once with
/// each atlas side, in the same rounds, each row named by its value and its plan's atlas
/// that size (the shadow maps' memory grows with it); a list with a value that is not a
/// number is a usage error naming it.
#[test]
fn a_parameter_with_several_values_is_measured_at_each() {
    let dir = tempfile::tempdir().unwrap();
    bench(&[
        "--scene",
        "builtin:spheres",
        "--pipeline",
        "pipelines/visibility_msaa_4x.ron",
        "--pipeline",
        NOAA,
        "--param",
        "shadow_map=512,2048",
        "--no-reference",
        "--out-dir",
        dir.path().to_str().unwrap(),
    ])
    .expect(0);
    let json = read_json(&dir.path().join("results.json"));
    let memory = |pipeline: &str| number(&row(&json, pipeline)["figures"], "memory.physical_bytes");
    let (small, large) = (
        memory("visibility_msaa_4x [shadow_map=512]"),
        memory("visibility_msaa_4x [shadow_map=2048]"),
    );
    // On lavapipe the hardware's depth32float atlas: 4 bytes a texel.
    assert_eq!(large - small, 4.0 * (2048.0 * 2048.0 - 512.0 * 512.0));
    let noaa = row(&json, "deferred_noaa [shadow_map=512]");
    assert!(noaa["figures"].is_object(), "{noaa:#}");
    assert_eq!(json["rows"].as_array().unwrap().len(), 4);
    bench(&[
        "--param",
        "shadow_map=512,big",
        "--out-dir",
        dir.path().to_str().unwrap(),
    ])
    .expect(2)
    .stderr_has("`big` (parameter shadow_map) is not a whole number");
}
