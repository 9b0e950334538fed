//! Presets: `Preset(base: "FILE.ron", passes: { "pass": (params: .., inputs: ..) })` is the
//! base graph file with those passes' parameters or inputs replaced; errors name the file
//! each part is written in.

use rgraph_core::file::{declared_params, load_file, ErrorKind, GraphParams, Registry};
use rgraph_core::CompileOptions;

use crate::ron_support::{folder, located_errors};

/// Two clears of "a" (the second modifies the first's version, so it reads it) and a
/// clear of "b" of another sample count parameter.
const BASE: &str = r#"Graph(
    resources: {
        "a": Texture(format: "rgba8unorm"),
        "b": Texture(format: "rgba8unorm", samples: Param(name: "msaa", default: 4)),
    },
    passes: [
        (name: "clear a", plugin: "clear", params: (color: (1.0, 0.0, 0.0, 1.0)), outputs: { "target": "a" }),
        (name: "clear b", plugin: "clear", outputs: { "target": "b" }),
    ],
    outputs: ["a", "b"],
)"#;

#[test]
fn a_preset_is_its_base_with_the_passes_it_names_changed() {
    let preset = r#"// Clears "a" green.
Preset(
    base: "base.ron",
    passes: { "clear a": (params: (color: (0.0, 1.0, 0.0, 1.0))) },
)"#;
    let edited = BASE.replace("color: (1.0, 0.0, 0.0, 1.0)", "color: (0.0, 1.0, 0.0, 1.0)");
    let dir = folder(&[
        ("base.ron", BASE),
        ("green.ron", preset),
        ("edited.ron", &edited),
    ]);
    let registry = Registry::with_builtins();
    let options = CompileOptions::default();
    let plan = |name: &str| {
        let loaded = load_file(dir.path().join(name), &registry).unwrap_or_else(|e| panic!("{e}"));
        format!("{:?}", loaded.compile(&options).unwrap().passes)
    };
    assert_eq!(plan("green.ron"), plan("edited.ron"));
    assert_ne!(plan("green.ron"), plan("base.ron"));
    // The base's parameters are the preset's.
    let declared = declared_params(dir.path().join("green.ron"), &registry).unwrap();
    assert_eq!(declared, GraphParams::new().with("msaa", 4));
}

#[test]
fn an_unknown_pass_is_an_error_in_the_preset_naming_the_base_s_passes() {
    let preset = "Preset(\n    base: \"base.ron\",\n    passes: { \"clear c\": (params: ()) },\n)";
    let dir = folder(&[("base.ron", BASE), ("p.ron", preset)]);
    let path = dir.path().join("p.ron");
    let found = located_errors(&path);
    assert_eq!(found.len(), 1, "{found:?}");
    assert_eq!(found[0].0, format!("{}:3:15", path.display()));
    assert!(
        matches!(&found[0].1, ErrorKind::UnknownPresetPass { pass, known, .. }
        if pass == "clear c" && known == "clear a, clear b")
    );
}

#[test]
fn a_bad_parameter_is_placed_in_the_preset_and_a_base_error_in_the_base() {
    let preset =
        "Preset(\n    base: \"base.ron\",\n    passes: { \"clear a\": (params: (colour: 1.0)) },\n)";
    let dir = folder(&[("base.ron", BASE), ("p.ron", preset)]);
    let path = dir.path().join("p.ron");
    let found = located_errors(&path);
    assert!(
        found[0].0.starts_with(&format!("{}:3:", path.display())),
        "{found:?}"
    );
    assert!(matches!(&found[0].1, ErrorKind::Params { pass, .. } if pass == "clear a"));

    // A slot the base's plugin has no use for is the base's line.
    let broken = BASE.replace(
        "outputs: { \"target\": \"b\" }",
        "inputs: { \"x\": \"a\" }, outputs: { \"target\": \"b\" }",
    );
    let preset = "Preset(base: \"base.ron\", passes: {})";
    let dir = folder(&[("base.ron", &broken), ("p.ron", preset)]);
    let found = located_errors(&dir.path().join("p.ron"));
    let base = dir.path().join("base.ron");
    assert!(
        found
            .iter()
            .all(|(at, _)| at.starts_with(&format!("{}:8:", base.display()))),
        "{found:?}"
    );
}

#[test]
fn a_missing_base_or_a_preset_of_a_preset_is_an_error_at_the_base() {
    let dir = folder(&[
        ("missing.ron", "Preset(base: \"nowhere.ron\")"),
        ("p.ron", "Preset(base: \"base.ron\")"),
        ("pp.ron", "Preset(base: \"p.ron\")"),
        ("base.ron", BASE),
    ]);
    let found = located_errors(&dir.path().join("missing.ron"));
    assert_eq!(
        found[0].0,
        format!("{}:1:14", dir.path().join("missing.ron").display())
    );
    assert!(
        matches!(&found[0].1, ErrorKind::PresetBase { base, .. } if base.ends_with("nowhere.ron"))
    );
    let found = located_errors(&dir.path().join("pp.ron"));
    assert!(matches!(&found[0].1, ErrorKind::PresetOfPreset { base } if base.ends_with("p.ron")));
}

#[test]
fn a_preset_gives_the_base_s_parameters_values_that_a_loader_s_replace() {
    let preset = "Preset(base: \"base.ron\", values: { \"msaa\": 1 })";
    let dir = folder(&[("base.ron", BASE), ("one.ron", preset)]);
    let path = dir.path().join("one.ron");
    let registry = Registry::with_builtins();
    let loaded = load_file(&path, &registry).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(loaded.params(), &GraphParams::new().with("msaa", 1));
    assert_eq!(
        declared_params(&path, &registry).unwrap(),
        GraphParams::new().with("msaa", 1)
    );
    let given = GraphParams::new().with("msaa", 8);
    let loaded = rgraph_core::file::load_file_with(&path, &registry, &given).unwrap();
    assert_eq!(loaded.params(), &given);
}

/// A preset may declare features of its own and mark the slots its changes add optional:
/// here a sky, cleared only where `sky` is set, that "present" blits where the plan keeps
/// it (`optional: ["src"]`), and nothing where it does not; the base never tests `sky`.
#[test]
fn a_preset_declares_features_and_optional_slots_for_what_it_adds() {
    let base = r#"Graph(
    resources: { "hdr": Texture(format: "rgba8unorm"), "color": Texture(format: "rgba8unorm") },
    passes: [
        (name: "clear", plugin: "clear", outputs: { "target": "hdr" }),
        (name: "present", plugin: "blit", inputs: { "src": "hdr" }, outputs: { "dst": "color" }),
    ],
    outputs: ["color"],
)"#;
    let preset = |optional: &str| {
        format!(
            r#"Preset(
    base: "base.ron",
    features: ["sky"],
    resources: {{ "sky": Texture(format: "rgba8unorm", when: "sky") }},
    passes: {{ "present": (inputs: {{ "src": "sky" }}{optional}) }},
    after: {{ "clear": [(name: "sky", plugin: "clear", when: "sky", outputs: {{ "target": "sky" }})] }},
)"#
        )
    };
    let dir = folder(&[
        ("base.ron", base),
        ("sky.ron", &preset(r#", optional: ["src"]"#)),
        ("required.ron", &preset("")),
    ]);
    let registry = Registry::with_builtins();
    let options = CompileOptions::default();
    let loaded = load_file(dir.path().join("sky.ron"), &registry).unwrap_or_else(|e| panic!("{e}"));
    assert!(loaded.graph.declared_features().contains("sky"));
    let present = |plan: &rgraph_core::Plan| {
        let pass = plan.passes.iter().find(|p| p.name == "present");
        pass.expect("present runs").clone()
    };
    let with = loaded
        .compile_for(&options, &rgraph_core::Features::from_iter(["sky"]))
        .unwrap();
    assert_eq!(present(&with).reads.len(), 1);
    let without = loaded
        .compile_for(&options, &rgraph_core::Features::new())
        .unwrap();
    assert!(present(&without).reads.is_empty());
    assert_eq!(
        present(&without).dropped_reads[0].why,
        r#""sky" is dropped: condition "sky" is false"#
    );
    // Without the preset's `optional` the read of the dropped sky is refused.
    let required = load_file(dir.path().join("required.ron"), &registry).unwrap();
    assert!(required
        .compile_for(&options, &rgraph_core::Features::new())
        .is_err());
}
