//! `rgraph render --samples N` (the graph file's `msaa` parameter) with a count the
//! device lacks: the compile for the opened device names each texture, its format, the
//! count and the counts the device has, before any GPU work, and no PNG appears. The GPU
//! tests run on lavapipe (the default adapter), which offers 1x and 4x only, so 8x is the
//! count it lacks. A file without the parameter is an error at its start; `explain
//! --samples 1` plans single-sampled textures.

use std::process::Command;

#[test]
fn an_eight_sample_pipeline_on_lavapipe_lists_the_counts_it_has() {
    let dir = tempfile::tempdir().expect("a temporary directory");
    let pipeline = "pipelines/deferred_msaa_4x.ron";
    let out = dir.path().join("frame.png");

    let run = Command::new(env!("CARGO_BIN_EXE_rgraph"))
        .args([
            "render",
            "--width",
            "64",
            "--height",
            "48",
            "--samples",
            "8",
        ])
        .args(["--pipeline", pipeline])
        .arg("--out")
        .arg(&out)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("the rgraph binary runs");
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(1), "{stderr}");
    let albedo = stderr
        .lines()
        .find(|l| l.contains("error: texture \"albedo\""))
        .unwrap_or_else(|| panic!("no error about \"albedo\" in:\n{stderr}"));
    // "albedo" is declared in the G-buffer part the pipeline uses.
    assert!(
        albedo.starts_with("pipelines/parts/gbuffer.ron:"),
        "the error starts with the position of the declaration: {albedo}"
    );
    assert!(
        albedo.contains("does not support 8x multisampling on llvmpipe")
            && albedo.ends_with("(supported: 1x, 4x)"),
        "{albedo}"
    );
    assert!(!out.exists(), "a failed render wrote {}", out.display());
}

#[test]
fn samples_for_a_file_without_the_parameter_is_an_error_at_its_start() {
    let dir = tempfile::tempdir().expect("a temporary directory");
    let out = dir.path().join("frame.png");
    let run = Command::new(env!("CARGO_BIN_EXE_rgraph"))
        .args([
            "render",
            "--width",
            "16",
            "--height",
            "16",
            "--samples",
            "4",
        ])
        .args(["--pipeline", "pipelines/deferred_noaa.ron", "--out"])
        .arg(&out)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("the rgraph binary runs");
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains(
            "pipelines/deferred_noaa.ron:1:1: error: parameter \"msaa\" is given a value (4), \
             but the file declares no parameter of that name (it declares: shadow_map)"
        ),
        "{stderr}"
    );
    assert!(!out.exists(), "a failed render wrote {}", out.display());
}

#[test]
fn explain_at_one_sample_plans_no_multisampled_texture() {
    let explain = |extra: &[&str]| {
        let run = Command::new(env!("CARGO_BIN_EXE_rgraph"))
            .args(["explain", "--pipeline", "pipelines/deferred_msaa_4x.ron"])
            .args(["--format", "json"])
            .args(extra)
            .current_dir(env!("CARGO_MANIFEST_DIR"))
            .output()
            .expect("the rgraph binary runs");
        assert_eq!(run.status.code(), Some(0));
        String::from_utf8(run.stdout).expect("UTF-8 JSON")
    };
    assert!(
        explain(&[]).contains("\"samples\": 4"),
        "the file's default is 4x"
    );
    assert!(!explain(&["--samples", "1"]).contains("\"samples\": 4"));
}

#[test]
fn explain_says_which_parameter_values_it_planned_with() {
    let explain = |extra: &[&str]| {
        let run = Command::new(env!("CARGO_BIN_EXE_rgraph"))
            .args(["explain", "--pipeline", "pipelines/deferred_msaa_4x.ron"])
            .args(extra)
            .current_dir(env!("CARGO_MANIFEST_DIR"))
            .output()
            .expect("the rgraph binary runs");
        assert_eq!(run.status.code(), Some(0));
        String::from_utf8(run.stdout).expect("UTF-8 text")
    };
    assert!(explain(&[]).starts_with(
        "parameters: msaa = 4 (the file's default), shadow_map = 4096 (the file's default)\n"
    ));
    assert!(explain(&["--samples", "1", "--param", "shadow_map=2048"])
        .starts_with("parameters: msaa = 1 (given), shadow_map = 2048 (given)\n"));
}
