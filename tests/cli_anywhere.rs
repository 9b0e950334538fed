//! The binary carries `pipelines/`, `shaders/` and `bench/graphs/`: run from a directory
//! without them it renders, explains and benches as from the repository root, and a file
//! on disk still overrides the built-in one.

use crate::cli_support;

use cli_support::rgraph_in;

#[test]
fn render_works_from_a_directory_without_the_repository() {
    let dir = tempfile::tempdir().unwrap();
    let run = rgraph_in(
        dir.path(),
        &[
            "render",
            "--width",
            "64",
            "--height",
            "48",
            "--out",
            "frame.png",
        ],
    )
    .expect(0);
    assert_eq!(run.stdout, "frame.png\n");
    let image = image::open(dir.path().join("frame.png"))
        .unwrap()
        .to_rgba8();
    assert_eq!(image.dimensions(), (64, 48));
    let mut colors: Vec<[u8; 4]> = image.pixels().map(|p| p.0).collect();
    colors.sort_unstable();
    colors.dedup();
    assert!(colors.len() > 50, "a flat image: {} colors", colors.len());
}

#[test]
fn a_generic_demo_finds_its_built_in_shaders() {
    let dir = tempfile::tempdir().unwrap();
    let run = rgraph_in(
        dir.path(),
        &["explain", "--pipeline", "pipelines/postprocess_demo.ron"],
    )
    .expect(0);
    assert!(run.stdout.contains("tonemap"), "{}", run.stdout);
    rgraph_in(
        dir.path(),
        &[
            "validate",
            "pipelines/postprocess_demo.ron",
            "shaders/gradient.wgsl",
        ],
    )
    .expect(0);
}

#[test]
fn a_file_on_disk_overrides_the_built_in_one() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("pipelines")).unwrap();
    std::fs::write(
        dir.path().join("pipelines/deferred_msaa_4x.ron"),
        "Graph(resources: {}, passes: [], outputs: [\"nothing\"])",
    )
    .unwrap();
    let run = rgraph_in(
        dir.path(),
        &[
            "render",
            "--pipeline",
            "pipelines/deferred_msaa_4x.ron",
            "--width",
            "8",
            "--height",
            "8",
            "--out",
            "frame.png",
        ],
    )
    .expect(1);
    run.stderr_has("pipelines/deferred_msaa_4x.ron:1:");
    assert!(!dir.path().join("frame.png").exists());
}

#[test]
fn bench_measures_the_unique_surfaces_bound_away_from_the_repository() {
    let dir = tempfile::tempdir().unwrap();
    let run = rgraph_in(
        dir.path(),
        &[
            "bench",
            "--scene",
            "builtin:unlit",
            "--pipeline",
            "pipelines/deferred_noaa.ron",
            "--width",
            "32",
            "--height",
            "24",
            "--frames",
            "1",
            "--warmup",
            "0",
            "--no-reference",
            "--out-dir",
            "out",
        ],
    )
    .expect(0);
    let results = std::fs::read_to_string(dir.path().join("out/results.json")).unwrap();
    let json: serde_json::Value = serde_json::from_str(&results).unwrap();
    let scene = &json["scenes"][0];
    assert_eq!(
        scene["unique_surfaces_error"],
        serde_json::Value::Null,
        "{}",
        run.stderr
    );
    assert_eq!(
        scene["unique_surfaces"]["graph"],
        "bench/graphs/unique_surfaces.ron"
    );
}
