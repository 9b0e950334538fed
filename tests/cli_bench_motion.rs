//! `rgraph bench --motion` as a user runs it: the built binary on lavapipe (unless
//! RGRAPH_ADAPTER says otherwise) at 64x36, no AA and TAA on builtin:spheres for three
//! moving frames, the last frame then timed in three interleaved rounds of one frame after
//! a warmup, with round 2 made ten times as long by the bench's test hook
//! (`RGRAPH_BENCH_FAKE_SLOW_ROUND`) so that the spread's flag shows; checked through
//! motion.json, motion.md and motion.png.

use serde_json::Value;

const PIPELINES: [&str; 2] = ["visibility_noaa", "taa"];
const ROUNDS: usize = 3;
const MOVING: usize = 3;

fn numbers(value: &Value) -> Vec<f64> {
    value
        .as_array()
        .unwrap_or_else(|| panic!("{value} is not an array"))
        .iter()
        .map(|v| v.as_f64().unwrap_or_else(|| panic!("{v} is not a number")))
        .collect()
}

#[test]
fn the_last_frame_is_timed_in_interleaved_rounds() {
    let dir = tempfile::tempdir().expect("a temporary directory");
    let out = dir.path().to_str().expect("temp paths are UTF-8");
    let run = std::process::Command::new(env!("CARGO_BIN_EXE_rgraph"))
        .args([
            "bench",
            "--motion",
            "orbit:10",
            "--motion-frames",
            "3",
            "--width",
            "64",
            "--height",
            "36",
            "--frames",
            "1",
            "--rounds",
            "3",
            "--warmup",
            "1",
            "--pipeline",
            "pipelines/visibility_noaa.ron",
            "--pipeline",
            "pipelines/taa.ron",
            "--out-dir",
            out,
        ])
        .env("RGRAPH_BENCH_FAKE_SLOW_ROUND", "2")
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("the rgraph binary runs");
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success(), "{stderr}");
    let json_path = dir.path().join("motion.json");
    assert_eq!(
        String::from_utf8_lossy(&run.stdout).trim(),
        json_path.display().to_string()
    );
    let json: Value = serde_json::from_str(&std::fs::read_to_string(&json_path).unwrap())
        .expect("motion.json is JSON");
    assert_eq!(
        (&json["frames"], &json["rounds"], &json["warmup"]),
        (&Value::from(1), &Value::from(ROUNDS), &Value::from(1)),
        "{json:#}"
    );
    assert_eq!(json["spread_limit"], 0.05);

    // Every round ran both pipelines, in the order they were given.
    let log = json["round_log"].as_array().expect("round_log is an array");
    assert_eq!(log.len(), ROUNDS, "{log:#?}");
    for (i, round) in log.iter().enumerate() {
        assert_eq!(round["round"], i + 1);
        assert_eq!(round["order"], serde_json::json!(PIPELINES), "{round:#}");
    }

    let rows = json["rows"].as_array().expect("rows is an array");
    let names: Vec<&str> = rows
        .iter()
        .map(|r| r["pipeline"].as_str().unwrap())
        .collect();
    assert_eq!(names, PIPELINES);
    for row in rows {
        let name = row["pipeline"].as_str().unwrap();
        let time = &row["gpu_frame_ms"];
        let rounds = numbers(&time["rounds"]);
        assert_eq!(rounds.len(), ROUNDS, "{name}: {time:#}");
        // The hook's round is the slowest by far, and the spread says so: the rows'
        // times come from the rounds, not from the sequence's frames.
        let slowest = (0..ROUNDS).max_by(|a, b| rounds[*a].total_cmp(&rounds[*b]));
        assert_eq!(slowest, Some(1), "{name}: {rounds:?}");
        let (median, min, max) = (
            time["median"].as_f64().unwrap(),
            time["min"].as_f64().unwrap(),
            time["max"].as_f64().unwrap(),
        );
        assert!(min < median && median < max, "{name}: {time:#}");
        assert!(time["spread"].as_f64().unwrap() > 0.05, "{name}: {time:#}");
        assert_eq!(row["flag"]["spread"], time["spread"], "{name}: {row:#}");
        // Each pass timed over the same rounds; TAA's own passes among TAA's.
        let passes = row["passes"].as_array().expect("passes is an array");
        assert!(
            passes.iter().all(|p| p["gpu_ms"]["rounds"]
                .as_array()
                .is_some_and(|r| r.len() == ROUNDS)),
            "{name}: {passes:#?}"
        );
        let pass_names: Vec<&str> = passes.iter().map(|p| p["name"].as_str().unwrap()).collect();
        if name == "taa" {
            assert!(pass_names.contains(&"taa"), "{pass_names:?}");
            assert!(
                pass_names.iter().any(|p| p.starts_with("motion vectors")),
                "{pass_names:?}"
            );
        }
        // The error figures as before: the last still frame, then each moving one.
        let flips = numbers(&row["flips"]);
        assert_eq!(flips.len(), 1 + MOVING, "{name}: {flips:?}");
        assert_eq!(flips[0], row["still_flip"].as_f64().unwrap());
        let sequence = flips[1..].iter().sum::<f64>() / MOVING as f64;
        assert!((sequence - row["sequence_flip"].as_f64().unwrap()).abs() < 1e-9);
        assert!(flips.iter().all(|f| (0.0..=1.0).contains(f)), "{flips:?}");
        assert!(row["instability"].as_f64().unwrap() >= 0.0);
    }

    let table = std::fs::read_to_string(dir.path().join("motion.md")).unwrap();
    assert!(
        table.contains(
            "| scene | pipeline | GPU ms | p10–p90 | spread | still FLIP | sequence FLIP \
             | instability (1/255) |"
        ),
        "{table}"
    );
    assert!(
        table.contains("Timed in 3 rounds (round_log in motion.json)"),
        "{table}"
    );
    for name in PIPELINES {
        let line = table
            .lines()
            .find(|l| l.starts_with(&format!("| builtin:spheres | {name} |")))
            .unwrap_or_else(|| panic!("no line for {name} in {table}"));
        let cells: Vec<&str> = line.split(" | ").collect();
        assert!(cells[2].ends_with('⚑'), "{line}");
        assert!(cells[3].contains('–'), "{line}");
        assert!(cells[4].ends_with('%'), "{line}");
        assert!(
            table.contains(&format!("\n- builtin:spheres: {name}: ")),
            "{table}"
        );
        assert!(
            table.contains(&format!("| builtin:spheres: {name} | shadow maps ")),
            "{table}"
        );
    }
    assert!(table.contains("⚑ Flagged"), "{table}");
    let chart = image::open(dir.path().join("motion.png")).expect("motion.png is an image");
    assert!(chart.width() > 0 && chart.height() > 0);
}
