//! The shipped pipelines keep their plans as they are rebuilt from parts
//! (`pipelines/parts/`): for every file in `pipelines/`, every set of its features and
//! each sample count it offers, the plan `explain` prints (less the `from` lines naming
//! the part a pass came from) hashes to the digest `fixtures/pipeline_plans.txt` holds.
//! Resources are compared by name, not by the order the file declares them in (a part's
//! resources are declared where the graph uses it): the resources section is sorted, and
//! each physical texture is named by the resources it holds, not by its number.
//! The digests were taken from the files as they were written out by hand, before any
//! was built from parts (commit 9e1f83d), but for two: `visibility_msaa_4x_fxaa.ron` is
//! new, and `deferred_msaa_4x_fxaa.ron`, made a preset of `deferred_msaa_4x.ron`, gained
//! its base's feature `background` and the pass it gates. The material layers' features
//! (`LAYERS`, which the G-buffer pipelines declare beside their own) add their targets
//! apart from the rest: they are tried all off with every set of the file's other
//! features, and each combination of `LAYER_SETS` with none and with all of them, so a
//! file of ten other features stays near 2^10 plans. So is `deformed` (declared by the
//! TAA presets, for their G-buffer's pose offset): tried off with every set, and on with
//! none and with all of the others, alone, on a device holding 64 bytes per sample, and
//! with every layer. A plan that changes on purpose
//! is blessed with
//! `RGRAPH_BLESS_PLANS=1 ./dev test --test integration pipeline_plans::`, and the diff of
//! the fixture shows which files and feature sets it touched.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use rgraph_core::file::{declared_params, load_file_with, GraphParams, Registry};
use rgraph_core::{explain, CompileOptions, Features, Plan};

const FIXTURE: &str = "tests/fixtures/pipeline_plans.txt";

/// The material layers' features (a scene's, and the device condition the G-buffer's
/// layers need), tried apart from a file's others.
const LAYERS: [&str; 6] = [
    "specular",
    "clearcoat",
    "clearcoat_normal",
    "sheen",
    "layer_lobes",
    "color_bytes_64",
];

/// The combinations of [`LAYERS`] tried (less those a file does not declare): none, each
/// layer alone, the coat with its own normal, and all of them, each on a device that
/// holds them.
const LAYER_SETS: [&[&str]; 6] = [
    &[],
    &["specular", "color_bytes_64"],
    &["clearcoat", "layer_lobes", "color_bytes_64"],
    &[
        "clearcoat",
        "clearcoat_normal",
        "layer_lobes",
        "color_bytes_64",
    ],
    &["sheen", "layer_lobes", "color_bytes_64"],
    &LAYERS,
];

/// A scene with skins or morph targets, tried apart as [`LAYERS`] are.
const DEFORMED: &str = "deformed";

/// The combinations with [`DEFORMED`] tried, where a file declares it (less the layers
/// it does not declare).
const DEFORMED_SETS: [&[&str]; 3] = [
    &[DEFORMED],
    &[DEFORMED, "color_bytes_64"],
    &[
        DEFORMED,
        "specular",
        "clearcoat",
        "clearcoat_normal",
        "sheen",
        "layer_lobes",
        "color_bytes_64",
    ],
];

/// The shipped graph files (not the parts they use), sorted.
fn pipelines() -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir("pipelines")
        .expect("run from the repository root")
        .map(|entry| entry.expect("a readable folder").path())
        .filter(|path| path.extension().is_some_and(|e| e == "ron"))
        .collect();
    files.sort();
    files
}

/// FNV-1a, 64 bits: stable across platforms and Rust releases, unlike std's hasher.
fn digest(text: &str) -> String {
    let hash = text.bytes().fold(0xcbf2_9ce4_8422_2325_u64, |hash, byte| {
        (hash ^ u64::from(byte)).wrapping_mul(0x0100_0000_01b3)
    });
    format!("{hash:016x}")
}

/// The plan as `explain` prints it, without the lines saying which part a pass is from,
/// its resources in the order of their names and its physical textures named by what
/// they hold.
fn written_out(plan: &Plan) -> String {
    let mut plan = plan.clone();
    for pass in &mut plan.passes {
        pass.origin = None;
    }
    let text = explain::text(&plan);
    let (head, rest) = text
        .split_once("\nresources:\n")
        .expect("a resources section");
    let (resources, rest) = rest
        .split_once("\nphysical textures:\n")
        .unwrap_or((rest, ""));
    let (textures, tail) = rest.split_once("\n\n").unwrap_or((rest, ""));
    // "#3 FORMAT SIZE ... holds a, b": what each number holds, and the lines unnumbered.
    let mut holds = std::collections::HashMap::new();
    let mut texture_lines: Vec<String> = Vec::new();
    for line in textures.lines() {
        let (number, description) = line.trim().split_once(' ').unwrap_or((line, ""));
        let held = description
            .rsplit_once(" holds ")
            .map_or("", |(_, held)| held);
        holds.insert(number.to_owned(), held.to_owned());
        texture_lines.push(description.to_owned());
    }
    texture_lines.sort();
    // A resource is its name line and the more indented lines under it.
    let mut blocks: Vec<String> = Vec::new();
    for line in resources.lines() {
        let line = match line.trim().strip_prefix("physical texture ") {
            Some(number) => format!("      physical texture holding {}", holds[number]),
            None => line.to_owned(),
        };
        match (line.starts_with("    "), blocks.last_mut()) {
            (true, Some(block)) => {
                block.push('\n');
                block.push_str(&line);
            }
            _ => blocks.push(line),
        }
    }
    blocks.sort();
    format!(
        "{head}\nresources:\n{}\nphysical textures:\n{}\n\n{tail}",
        blocks.join("\n"),
        texture_lines.join("\n")
    )
}

/// One line per file, parameter values and feature set: `FILE PARAMS FEATURES DIGEST`,
/// and the plan's text by line, for messages.
fn plans(registry: &Registry) -> Vec<(String, String)> {
    let mut lines = Vec::new();
    for path in pipelines() {
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        let declared = declared_params(&path, registry).unwrap_or_else(|e| panic!("{e}"));
        let mut values = vec![GraphParams::new()];
        if declared.get("msaa").is_some_and(|msaa| msaa != 1) {
            values.push(GraphParams::new().with("msaa", 1));
        }
        for params in values {
            let shown_params = match params.get("msaa") {
                Some(msaa) => format!("msaa={msaa}"),
                None => "defaults".to_owned(),
            };
            // A value the file refuses (a demo written for multisampled targets only)
            // must be refused alike.
            let Ok(loaded) = load_file_with(&path, registry, &params) else {
                lines.push((format!("{name} {shown_params} refused"), String::new()));
                continue;
            };
            let declared: Vec<&str> = loaded.graph.declared_features().iter().collect();
            let (apart, features): (Vec<&str>, Vec<&str>) = declared
                .iter()
                .partition(|f| LAYERS.contains(f) || **f == DEFORMED);
            assert!(
                features.len() <= 10,
                "{name}: too many features to try every set"
            );
            let all_others = (1u32 << features.len()) - 1;
            let mut sets: Vec<(u32, &[&str])> =
                (0..=all_others).map(|set| (set, &[][..])).collect();
            let layers = apart.iter().any(|f| LAYERS.contains(f));
            let deformed = apart.contains(&DEFORMED);
            let combinations = (LAYER_SETS[1..].iter().filter(|_| layers))
                .chain(DEFORMED_SETS.iter().filter(|_| deformed));
            for combination in combinations {
                sets.extend([(0, *combination), (all_others, *combination)]);
            }
            let mut tried = std::collections::HashSet::new();
            for (set, layer_set) in sets {
                let mut on = Features::new();
                for (i, feature) in features.iter().enumerate() {
                    if set & (1 << i) != 0 {
                        on.insert(*feature);
                    }
                }
                for feature in layer_set.iter().filter(|f| apart.contains(f)) {
                    on.insert(*feature);
                }
                // A combination whose layers the file does not declare is a set tried.
                if !tried.insert(on.to_string()) {
                    continue;
                }
                let defaults = CompileOptions::default();
                let options = CompileOptions {
                    output_size: (1280, 720),
                    profile: defaults.profile.granting(&on),
                };
                // A set the file refuses (conditions that cannot hold together) must be
                // refused alike; where the error is placed moves with the parts.
                let text = match loaded.compile_for(&options, &on) {
                    Ok(plan) => written_out(&plan),
                    Err(_) => "refused".to_owned(),
                };
                let shown: Vec<&str> = on.iter().collect();
                let shown = match shown.is_empty() {
                    true => "-".to_owned(),
                    false => shown.join(","),
                };
                lines.push((
                    format!("{name} {shown_params} {shown} {}", digest(&text)),
                    text,
                ));
            }
        }
    }
    lines
}

#[test]
fn every_shipped_pipeline_keeps_the_plans_it_had_written_out() {
    let mut registry = Registry::with_builtins();
    rgraph_passes::register(&mut registry, None);
    // The demo pipelines' shaders, as `rgraph` allows them.
    registry
        .allow_graph_root("shaders")
        .expect("the shaders folder");
    let plans = plans(&registry);
    let found: String = plans.iter().fold(String::new(), |mut out, (line, _)| {
        let _ = writeln!(out, "{line}");
        out
    });
    if std::env::var_os("RGRAPH_BLESS_PLANS").is_some() {
        std::fs::write(FIXTURE, &found).expect("a writable fixture");
        return;
    }
    let recorded = std::fs::read_to_string(Path::new(FIXTURE)).expect("the recorded digests");
    let recorded: Vec<&str> = recorded.lines().collect();
    let changed: Vec<&(String, String)> = plans
        .iter()
        .filter(|(line, _)| !recorded.contains(&line.as_str()))
        .collect();
    let gone: Vec<&&str> = recorded
        .iter()
        .filter(|line| !plans.iter().any(|(found, _)| found == *line))
        .collect();
    if let Some((line, text)) = changed.first() {
        panic!(
            "{} plans differ from the recorded ones (first: {line}), {} recorded are gone; \
             the first one's plan now:\n{text}\nchanged: {:?}\ngone: {gone:?}",
            changed.len(),
            gone.len(),
            changed.iter().map(|(line, _)| line).collect::<Vec<_>>(),
        );
    }
    assert!(
        gone.is_empty(),
        "recorded plans no file gives any more: {gone:?}"
    );
    // Not vacuous: every shipped file, with its feature sets.
    assert!(
        plans.len() >= pipelines().len() * 2,
        "{} plans",
        plans.len()
    );
}

/// The `passes` of a graph file, each as written (a preset has none of its own).
#[derive(serde::Deserialize)]
#[serde(rename = "Graph")]
struct Passes<'a> {
    #[serde(borrow, default)]
    passes: Vec<&'a ron::value::RawValue>,
}

/// Each pass a pipeline file writes out (not a use of a part), its layout, comments and
/// trailing commas dropped: what "the same pass" means below.
fn written_passes(path: &Path) -> Vec<String> {
    let text = std::fs::read_to_string(path).expect("a readable pipeline");
    let options = ron::Options::default().with_default_extension(
        ron::extensions::Extensions::UNWRAP_VARIANT_NEWTYPES
            | ron::extensions::Extensions::IMPLICIT_SOME,
    );
    let file: Passes = match options.from_str(&text) {
        Ok(file) => file,
        // A preset writes no pass of its own (only changes and parts it adds).
        Err(_) if text.contains("\nPreset(") => return Vec::new(),
        Err(e) => panic!("{}: {e}", path.display()),
    };
    file.passes
        .iter()
        .map(|pass| {
            let code: Vec<&str> = pass
                .get_ron()
                .lines()
                .map(|line| line.split("//").next().unwrap_or(""))
                .collect();
            let words = code
                .join(" ")
                .split_whitespace()
                .collect::<Vec<_>>()
                .join(" ");
            words
                .replace(", )", ")")
                .replace(", }", "}")
                .replace(",)", ")")
        })
        .filter(|pass| !pass.starts_with("(part:"))
        .collect()
}

/// What pipelines share is written once, in a part: no pass is written out, the same, in
/// two pipeline files.
#[test]
fn no_pass_is_written_in_two_pipeline_files() {
    let mut seen: std::collections::HashMap<String, PathBuf> = std::collections::HashMap::new();
    let mut repeated = Vec::new();
    let mut passes = 0;
    for path in pipelines() {
        for pass in written_passes(&path) {
            passes += 1;
            match seen.get(&pass) {
                Some(first) if *first != path => repeated.push(format!(
                    "{} and {}: {pass}",
                    first.display(),
                    path.display()
                )),
                _ => {
                    seen.insert(pass, path.clone());
                }
            }
        }
    }
    assert!(
        repeated.is_empty(),
        "passes written in two files:\n{}",
        repeated.join("\n")
    );
    // Not vacuous: the files' own passes were read.
    assert!(passes > 50, "{passes} passes read");
}
