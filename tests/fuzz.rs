//! Fuzzing, a fixed budget on every test run (CI included): the RON loader, compile and
//! explain, the glTF loader, scene analysis and statistics, and the command-line parser,
//! each on mutations of committed files. No input may panic or hang; every one ends in a
//! value or an error.
//! See `fuzz_support` for the harness and README "Fuzzing" for a longer run's counts.

use crate::fuzz_support;

use std::path::PathBuf;

use fuzz_support::{fuzz, iterations, seeds};
use rgraph_core::file::{load_str, Registry};
use rgraph_core::{explain, CompileOptions};
use rgraph_scene::analysis::Analysis;
use rgraph_scene::{AssetPolicy, Scene};

/// Where the graph-file target plants the files its path-attack mutants name (see
/// fuzz_support's tokens), outside every folder graph files may read.
const SECRET_FOLDER: &str = "/tmp/rgraph-fuzz-secret";

/// What the planted files hold.
const SECRET: &str = "SECRET-5c1d";

/// The command-line definition itself, compiled into this test.
#[allow(dead_code)]
#[path = "../src/cli.rs"]
mod cli;

#[test]
fn graph_files_load_and_compile_or_fail_with_errors() {
    let seeds = seeds(
        &[
            "pipelines",
            "tests/fixtures",
            "graph-core/tests/fixtures",
            "graph-core/tests/fixtures/valid/graphs",
            "tests/fuzz_corpus/ron",
        ],
        &[".ron"],
    );
    fuzz("ron", seeds, iterations(3_000), || {
        let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
        let mut registry = Registry::with_builtins();
        rgraph_passes::register(&mut registry, None);
        // The seeds name the shipped shaders from pipelines/ and tests/fixtures/.
        registry
            .allow_graph_root(&root)
            .expect("the repository is a folder");
        // Files outside every allowed folder, which the mutants' path attacks name: no
        // error may quote them.
        let secrets = std::path::Path::new(SECRET_FOLDER);
        std::fs::create_dir_all(secrets).expect("a folder for the planted files");
        for name in ["secret.ron", "secret.wgsl"] {
            std::fs::write(secrets.join(name), format!("{SECRET}(\n")).expect("planted");
        }
        // As if in pipelines/, so the seeds' relative shader paths resolve.
        let path = root.join("pipelines/fuzzed.ron");
        Box::new(move |input| {
            let text = String::from_utf8_lossy(input);
            let loaded = match load_str(&path, &text, &registry) {
                Ok(loaded) => loaded,
                Err(errors) => {
                    let message = errors.to_string();
                    assert!(
                        !message.contains(SECRET),
                        "a planted file leaked: {message}"
                    );
                    return false;
                }
            };
            // What `explain` checks (as `validate` does) and prints of a plan, in every
            // format. A file `validate` accepts compiles for no features too.
            let options = CompileOptions::default();
            let validated = loaded.validate(&options);
            let compiled = loaded.compile(&options);
            assert!(
                validated.is_err() || compiled.is_ok(),
                "validate accepted a file that does not compile"
            );
            if let Ok(plan) = compiled {
                let _ = (
                    explain::text(&plan),
                    explain::dot(&plan),
                    explain::json(&plan),
                );
            }
            true
        })
    })
    .assert_clean();
}

#[test]
fn gltf_files_load_and_analyse_or_fail_with_errors() {
    let seeds = seeds(
        &[
            "scene/tests/fixtures",
            "scene/tests/fixtures/external",
            "tests/fuzz_corpus/gltf",
        ],
        &[".gltf", ".glb"],
    );
    fuzz("gltf", seeds, iterations(3_000), || {
        // A folder like a downloaded asset's: the external fixture's buffer beside the
        // file, another file outside it that no URI may reach.
        let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("fuzz-gltf");
        let asset = dir.join("asset");
        std::fs::create_dir_all(&asset).expect("a fuzz directory");
        let fixtures = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("scene/tests/fixtures");
        let bin = fixtures.join("external/lights_cameras.bin");
        std::fs::copy(&bin, asset.join("lights_cameras.bin")).expect("the buffer copies");
        std::fs::copy(&bin, dir.join("outside.bin")).expect("the buffer copies");
        let file = asset.join("fuzzed.gltf");
        let policy = AssetPolicy {
            max_bytes: 1 << 20,
            ..AssetPolicy::default()
        };
        Box::new(move |input| {
            std::fs::write(&file, input).expect("the input is written");
            let Ok(scene) = Scene::from_gltf_with(&file, &policy) else {
                return false;
            };
            // What `explain --scene` and `render` print of it.
            let _ = (Analysis::of(&scene, (64, 48)), scene.stats().to_string());
            true
        })
    })
    .assert_clean();
}

#[test]
fn command_lines_parse_or_fail_with_usage_errors() {
    let seeds = seeds(&["tests/fuzz_corpus/cli"], &[".args"]);
    fuzz("cli", seeds, iterations(20_000), || {
        Box::new(|input| {
            // One argument a line, as the corpus files are written.
            let text = String::from_utf8_lossy(input);
            let args = std::iter::once("rgraph").chain(text.lines());
            <cli::Cli as clap::Parser>::try_parse_from(args).is_ok()
        })
    })
    .assert_clean();
}

/// The harness itself: a planted panic is found, saved and reported.
#[test]
fn the_harness_finds_a_planted_crash() {
    let report = fuzz("planted", vec![b"(1, 2)".to_vec()], 2_000, || {
        Box::new(|input| {
            assert!(!input.windows(3).any(|w| w == b"NaN"), "NaN reached");
            true
        })
    });
    assert_eq!(
        report.crashes.len(),
        fuzz_support::MAX_CRASHES,
        "the run stops there"
    );
    assert!(
        report.executions < 2_001,
        "the run went on after the crashes"
    );
    assert!(
        report.crashes[0].ends_with(": NaN reached"),
        "{}",
        report.crashes[0]
    );
    let saved = report.crashes[0].split(": ").next().unwrap();
    let input = std::fs::read(saved).expect("the crashing input is saved");
    assert!(input.windows(3).any(|w| w == b"NaN"));
}
