//! The command line against hostile and careless input (issues 36 and 44): graph files
//! kept inside their folders (`--graph-root` widens them), `explain` checking as
//! `validate` does, and the flags that were refused late, quoted raw or misnamed. No GPU:
//! `validate` and `explain` run without one, and the flag checks stop before one opens.

use crate::cli_support;

use std::path::Path;

use cli_support::{rgraph, rgraph_in, Run};

/// What the planted file outside the graph's folder holds: no output may show it.
const SECRET: &str = "SECRET-2b9e";

/// `graphs/` for graph files, `outside/secret.ron` beside it (and, on Unix,
/// `graphs/link.ron` leading to it).
fn planted() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir_all(dir.path().join("graphs")).unwrap();
    std::fs::create_dir_all(dir.path().join("outside")).unwrap();
    let secret = dir.path().join("outside/secret.ron");
    std::fs::write(&secret, format!("{SECRET}(\n")).unwrap();
    #[cfg(unix)]
    std::os::unix::fs::symlink(&secret, dir.path().join("graphs/link.ron")).unwrap();
    dir
}

fn no_secret(run: &Run) {
    assert!(
        !run.stdout.contains(SECRET) && !run.stderr.contains(SECRET),
        "the refused file's content was printed:\n{}\n{}",
        run.stdout,
        run.stderr
    );
}

fn path(p: &Path) -> &str {
    p.to_str().expect("temporary paths are UTF-8")
}

#[test]
fn validate_and_explain_refuse_a_preset_base_outside_the_folder() {
    let dir = planted();
    let file = dir.path().join("graphs/p.ron");
    let mut bases = vec![
        path(&dir.path().join("outside/secret.ron")).to_owned(),
        "../outside/secret.ron".to_owned(),
    ];
    if cfg!(unix) {
        bases.push("link.ron".to_owned());
    }
    for base in bases {
        std::fs::write(&file, format!("Preset(base: \"{base}\")")).unwrap();
        let run = rgraph(&["validate", path(&file)]).expect(1);
        no_secret(&run);
        let line = format!(
            "{}:1:14: error: the preset's base \"{base}\" ",
            file.display()
        );
        assert!(run.stdout.starts_with(&line), "{}", run.stdout);
        let run = rgraph(&["explain", "--pipeline", path(&file)]).expect(1);
        no_secret(&run);
        assert!(run.stderr.starts_with(&line), "{}", run.stderr);
    }
}

#[test]
fn graph_root_lets_graph_files_reach_another_folder() {
    let dir = planted();
    let shared = dir.path().join("outside/shared");
    std::fs::create_dir_all(&shared).unwrap();
    let base = r#"Graph(
    resources: { "c": Texture(format: "rgba8unorm") },
    passes: [(name: "clear", plugin: "clear", outputs: { "target": "c" })],
    outputs: ["c"],
)"#;
    std::fs::write(shared.join("base.ron"), base).unwrap();
    let file = dir.path().join("graphs/p.ron");
    std::fs::write(&file, r#"Preset(base: "../outside/shared/base.ron")"#).unwrap();
    let refused = rgraph(&["validate", path(&file)]).expect(1);
    assert!(
        refused.stdout.contains(
            "points to /", // the folder, made absolute
        ) && refused
            .stdout
            .contains("another is allowed with --graph-root DIR"),
        "{}",
        refused.stdout
    );
    rgraph(&["validate", "--graph-root", path(&shared), path(&file)]).expect(0);
    rgraph(&[
        "explain",
        "--graph-root",
        path(&shared),
        "--pipeline",
        path(&file),
    ])
    .expect(0);
    // The flag names folders that exist.
    let missing = dir.path().join("missing");
    rgraph(&["validate", "--graph-root", path(&missing), path(&file)])
        .expect(2)
        .stderr_has("for '--graph-root <DIR>'")
        .stderr_has("is not a folder that exists");
    rgraph(&["validate", "--graph-root", path(&file), path(&file)])
        .expect(2)
        .stderr_has(&format!(
            "invalid value '{0}' for '--graph-root <DIR>': {0} is a file, not a folder",
            file.display()
        ));
}

#[test]
fn asset_root_must_be_an_existing_folder_and_says_which_flag() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("f.txt");
    std::fs::write(&file, "x").unwrap();
    let explain = |root: &Path| {
        rgraph(&[
            "explain",
            "--pipeline",
            "pipelines/deferred_msaa_4x.ron",
            "--asset-root",
            path(root),
        ])
    };
    explain(&file).expect(2).stderr_has(&format!(
        "invalid value '{0}' for '--asset-root <DIR>': {0} is a file, not a folder",
        file.display()
    ));
    explain(&dir.path().join("missing"))
        .expect(2)
        .stderr_has("for '--asset-root <DIR>'")
        .stderr_has("is not a folder that exists");
}

#[test]
fn explain_fails_where_validate_does_under_a_condition_off_by_default() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("blend.ron");
    std::fs::write(
        &file,
        r#"Graph(
    features: ["blend"],
    resources: {
        "c": Texture(format: "rgba8unorm"),
        "m": Texture(format: "rgba8unorm", size: Absolute(64, 64), mips: 2048, when: "blend"),
    },
    passes: [
        (name: "clear c", plugin: "clear", outputs: { "target": "c" }),
        (name: "clear m", plugin: "clear", when: "blend", outputs: { "target": "m" }),
    ],
    outputs: ["c"],
)"#,
    )
    .unwrap();
    let error = format!(
        "{}:5:9: error: \"m\": 64x64 has at most 7 mips, 2048 were asked for",
        file.display()
    );
    let run = rgraph(&["validate", path(&file)]).expect(1);
    assert_eq!(run.stdout.trim_end(), error);
    let run = rgraph(&["explain", "--pipeline", path(&file)]).expect(1);
    assert_eq!(run.stderr.trim_end(), error);
    assert_eq!(run.stdout, "", "no plan is printed for an invalid file");
}

#[test]
fn a_preset_s_input_cycle_is_reported_at_the_preset_s_line() {
    let dir = tempfile::tempdir().unwrap();
    let base = r#"Graph(
    resources: { "a": Texture(format: "rgba8unorm"), "b": Texture(format: "rgba8unorm") },
    passes: [
        (name: "first", plugin: "blit", inputs: { "src": "b0" }, outputs: { "dst": "a" }),
        (name: "second", plugin: "blit", inputs: { "src": "a" }, outputs: { "dst": "b" }),
        (name: "zero", plugin: "clear", outputs: { "target": "b0" }),
    ],
    outputs: ["b"],
)"#;
    let base = base.replace(
        r#""b": Texture(format: "rgba8unorm") }"#,
        r#""b": Texture(format: "rgba8unorm"), "b0": Texture(format: "rgba8unorm") }"#,
    );
    std::fs::write(dir.path().join("base.ron"), base).unwrap();
    let preset = dir.path().join("cycle.ron");
    std::fs::write(
        &preset,
        "Preset(\n    base: \"base.ron\",\n    passes: { \"first\": (inputs: { \"src\": \"b\" }) },\n)",
    )
    .unwrap();
    let run = rgraph(&["validate", path(&preset)]).expect(1);
    assert_eq!(
        run.stdout.trim_end(),
        format!(
            "{}:3:42: error: cycle: passes \"first\", \"second\" must each run before the other \
             (through \"b\", \"a\")",
            preset.display()
        )
    );
}

#[test]
fn a_graph_file_that_is_not_utf8_is_placed_at_its_first_bad_byte() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("latin1.ron");
    let text = b"Graph(\n  resources: {},\n  passes: [(name: \"caf\xe9\", plugin: \"clear\")],\n)";
    std::fs::write(&file, text).unwrap();
    let run = rgraph(&["validate", path(&file)]).expect(1);
    assert_eq!(
        run.stdout.trim_end(),
        format!(
            "{}:3:23: error: not UTF-8 text: byte 0xE9 cannot stand here; graph files are UTF-8",
            file.display()
        )
    );
}

#[test]
fn a_preset_s_built_in_base_is_found_however_its_path_is_typed() {
    // A user's preset in a folder called pipelines/, over the built-in base it names.
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir_all(dir.path().join("pipelines")).unwrap();
    let preset = dir.path().join("pipelines/mine.ron");
    std::fs::write(&preset, r#"Preset(base: "deferred_msaa_4x.ron")"#).unwrap();
    rgraph_in(dir.path(), &["validate", "pipelines/mine.ron"]).expect(0);
    rgraph_in(dir.path(), &["validate", path(&preset)]).expect(0);
}

#[test]
fn parameter_values_too_large_say_so() {
    rgraph(&[
        "explain",
        "--pipeline",
        "pipelines/particles_low_res.ron",
        "--param",
        "scale=99999999999",
    ])
    .expect(2)
    .stderr_has("`99999999999` (parameter scale) is too large (at most 4294967295)");
}

#[test]
fn an_output_path_naming_a_folder_is_refused_before_anything_renders() {
    let run = rgraph(&["render", "--out", "nowhere/x.png/"]).expect(2);
    run.stderr_has("nowhere/x.png/ ends with a path separator, so it names a folder, not a file");
    assert!(!run.stderr.contains("load scene"), "{}", run.stderr);
}

#[test]
fn an_exposure_that_would_overflow_tone_mapping_is_refused_naming_the_limit() {
    let run = rgraph(&["render", "--out", "x.png", "--exposure", "1e25"]).expect(2);
    run.stderr_has(
        "invalid value '1e25' for '--exposure <E|auto>': 1e25 is too large (at most 1e12)",
    );
    assert!(!run.stderr.contains("load scene"), "{}", run.stderr);
}

#[test]
fn an_adapter_matching_nothing_is_quoted_once_and_the_adapters_listed() {
    let dir = tempfile::tempdir().unwrap();
    let profile = dir.path().join("profile.json");
    let run = rgraph(&[
        "adapters",
        "--adapter",
        "nosuch",
        "--save-profile",
        path(&profile),
    ])
    .expect(2);
    run.stderr_has("error: no adapter matches \"nosuch\" (adapters: ");
    assert!(!run.stderr.contains("\"\"nosuch\"\""), "{}", run.stderr);
    assert!(!profile.exists());
}
