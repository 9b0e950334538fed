//! `rgraph render` with a sample count the device lacks: the compile for the opened
//! device names each texture, its format, the count and the counts the device has, before
//! any GPU work, and no PNG appears. The GPU tests run on lavapipe (the default adapter),
//! which offers 1x and 4x only, so 8x is the count it lacks.

use std::process::Command;

#[test]
fn an_eight_sample_pipeline_on_lavapipe_lists_the_counts_it_has() {
    let dir = tempfile::tempdir().expect("a temporary directory");
    let default = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("pipelines/deferred_msaa_4x.ron"),
    )
    .expect("the default pipeline exists");
    assert!(default.contains("samples: 4"), "the default pipeline is 4x");
    let pipeline = dir.path().join("deferred_msaa_8x.ron");
    std::fs::write(&pipeline, default.replace("samples: 4", "samples: 8")).expect("write");
    let out = dir.path().join("frame.png");

    let run = Command::new(env!("CARGO_BIN_EXE_rgraph"))
        .args(["render", "--width", "64", "--height", "48", "--pipeline"])
        .arg(&pipeline)
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
    assert!(
        albedo.starts_with(&format!("{}:", pipeline.display())),
        "the error starts with the file's position: {albedo}"
    );
    assert!(
        albedo.contains("does not support 8x multisampling on llvmpipe")
            && albedo.ends_with("(supported: 1x, 4x)"),
        "{albedo}"
    );
    assert!(!out.exists(), "a failed render wrote {}", out.display());
}
