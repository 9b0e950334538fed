//! Parts: `Part(takes: {..}, gives: {..}, features: [..], resources: {..}, passes: [..])`
//! files, used from a graph's `passes` as `(part: "FILE.ron", inputs: {..}, outputs: {..})`.
//! A use writes out as the graph written by hand; each use gets names of its own; errors
//! about a use name the part's position and the use's; presets add and remove passes.

use std::path::Path;

use rgraph_core::file::{load_file, ErrorKind, Registry};
use rgraph_core::{explain, CompileOptions, Features, Plan};

use crate::ron_support::{folder, located_errors};

/// Clears a texture of its own and copies it into what it gives: the texture it takes
/// is cleared first, under the part's condition.
const TINT: &str = r#"// Clears "base" and tints what it gives.
Part(
    takes: { "base": Texture(format: "rgba8unorm") },
    gives: { "out": Texture(format: "rgba8unorm") },
    features: ["tinted"],
    resources: {
        "scratch": Texture(format: "rgba8unorm"),
        "out": Texture(format: "rgba8unorm"),
    },
    passes: [
        (name: "clear", plugin: "clear", when: "tinted",
         inputs: { "target": "base" }, outputs: { "target": "cleared" }),
        (name: "scratch", plugin: "clear", outputs: { "target": "scratch" }),
        (name: "copy", plugin: "blit", inputs: { "src": "scratch" }, outputs: { "dst": "out" }),
    ],
)"#;

fn plan(path: &Path, features: &[&str]) -> Plan {
    let loaded = load_file(path, &Registry::with_builtins()).unwrap_or_else(|e| panic!("{e}"));
    let mut on = Features::new();
    for feature in features {
        on.insert(*feature);
    }
    loaded
        .compile_for(&CompileOptions::default(), &on)
        .unwrap_or_else(|e| panic!("{e}"))
}

/// The plan as text, without the `from` lines a part's passes add.
fn written_out(plan: &Plan) -> String {
    let mut plan = plan.clone();
    for pass in &mut plan.passes {
        pass.origin = None;
    }
    explain::text(&plan)
}

const GRAPH: &str = r#"Graph(
    features: ["tinted"],
    resources: {
        "a": Texture(format: "rgba8unorm"),
        // "b" is the texture the part declares and gives.
    },
    passes: [
        (name: "clear a", plugin: "clear", outputs: { "target": "a" }),
        (part: "parts/tint.ron", when: "tinted", inputs: { "base": "a" }, outputs: { "out": "b" }),
    ],
    outputs: ["b", "cleared"],
)"#;

#[test]
fn a_use_compiles_to_the_plan_of_the_graph_written_out() {
    let by_hand = r#"Graph(
    features: ["tinted"],
    resources: {
        "a": Texture(format: "rgba8unorm"),
        "scratch": Texture(format: "rgba8unorm", when: "tinted"),
        "b": Texture(format: "rgba8unorm", when: "tinted"),
    },
    passes: [
        (name: "clear a", plugin: "clear", outputs: { "target": "a" }),
        (name: "clear", plugin: "clear", when: "tinted & tinted",
         inputs: { "target": "a" }, outputs: { "target": "a_cleared" }),
        (name: "scratch", plugin: "clear", when: "tinted", outputs: { "target": "scratch" }),
        (name: "copy", plugin: "blit", when: "tinted", inputs: { "src": "scratch" }, outputs: { "dst": "b" }),
    ],
    outputs: ["b", "a_cleared"],
)"#;
    // "cleared" is the part's own name for the version it writes: unbound, it keeps it.
    let by_hand = by_hand.replace("a_cleared", "cleared");
    let dir = folder(&[
        ("g.ron", GRAPH),
        ("parts/tint.ron", TINT),
        ("hand.ron", &by_hand),
    ]);
    let used = plan(&dir.path().join("g.ron"), &["tinted"]);
    assert_eq!(
        written_out(&used),
        written_out(&plan(&dir.path().join("hand.ron"), &["tinted"]))
    );
    // Explain says where each pass of the part came from.
    let text = explain::text(&plan(&dir.path().join("g.ron"), &["tinted"]));
    let part = dir.path().join("parts/tint.ron");
    let used_at = format!("{}:9:16", dir.path().join("g.ron").display());
    assert!(
        text.contains(&format!("from    {} (used at {used_at})", part.display())),
        "{text}"
    );
}

#[test]
fn two_uses_of_one_part_get_names_of_their_own_from_their_prefixes() {
    let graph = r#"Graph(
    features: ["tinted"],
    resources: { "a": Texture(format: "rgba8unorm"), "b": Texture(format: "rgba8unorm") },
    passes: [
        (name: "clear a", plugin: "clear", outputs: { "target": "a" }),
        (part: "parts/tint.ron", prefix: "left ", inputs: { "base": "a" }),
        (part: "parts/tint.ron", prefix: "right ", inputs: { "base": "b" }),
        (name: "clear b", plugin: "clear", outputs: { "target": "b" }),
    ],
    outputs: ["left out", "right out", "left cleared", "right cleared"],
)"#;
    let dir = folder(&[("g.ron", graph), ("parts/tint.ron", TINT)]);
    let plan = plan(&dir.path().join("g.ron"), &["tinted"]);
    let mut names: Vec<&str> = plan.passes.iter().map(|p| p.name.as_str()).collect();
    names.sort();
    // ("clear a" and "clear b" are culled: the parts' clears overwrite what they wrote.)
    assert_eq!(
        names,
        [
            "left clear",
            "left copy",
            "left scratch",
            "right clear",
            "right copy",
            "right scratch"
        ]
    );
    let resources: Vec<&str> = plan.resources.iter().map(|r| r.name.as_str()).collect();
    for own in ["left scratch", "right scratch", "left out", "right out"] {
        assert!(resources.contains(&own), "{own} in {resources:?}");
    }

    // The same part twice under one prefix: names would collide.
    let twice = graph.replace("prefix: \"right \", ", "prefix: \"left \", ");
    let dir = folder(&[("g.ron", &twice), ("parts/tint.ron", TINT)]);
    let path = dir.path().join("g.ron");
    let found = located_errors(&path);
    assert_eq!(found.len(), 1, "{found:?}");
    assert_eq!(found[0].0, format!("{}:7:16", path.display()));
    let message = found[0].1.to_string();
    assert!(
        message.contains(&format!("(first at {}:6:16)", path.display())),
        "{message}"
    );
}

#[test]
fn a_binding_of_the_wrong_format_names_the_part_and_the_use() {
    let graph = GRAPH.replace(
        "\"a\": Texture(format: \"rgba8unorm\")",
        "\"a\": Texture(format: \"rgba16float\")",
    );
    let dir = folder(&[("g.ron", &graph), ("parts/tint.ron", TINT)]);
    let path = dir.path().join("g.ron");
    let found = located_errors(&path);
    assert_eq!(found.len(), 1, "{found:?}");
    // At the use's binding, naming the part's interface.
    assert_eq!(found[0].0, format!("{}:9:68", path.display()));
    let part = dir.path().join("parts/tint.ron");
    assert_eq!(
        found[0].1.to_string(),
        format!(
            "part {} takes \"base\" as a texture of format rgba8unorm ({}:3:14), but in this \
             use it is \"a\", a texture of format rgba16float",
            part.display(),
            part.display()
        )
    );
}

#[test]
fn a_use_that_leaves_a_taken_resource_unbound_names_both_places() {
    let graph = GRAPH.replace("inputs: { \"base\": \"a\" }, ", "");
    let dir = folder(&[("g.ron", &graph), ("parts/tint.ron", TINT)]);
    let path = dir.path().join("g.ron");
    let found = located_errors(&path);
    assert_eq!(found[0].0, format!("{}:9:16", path.display()), "{found:?}");
    let part = dir.path().join("parts/tint.ron");
    assert!(
        matches!(&found[0].1, ErrorKind::PartUnbound { slot, at, .. }
            if slot == "base" && at.to_string() == format!("{}:3:14", part.display())),
        "{found:?}"
    );

    // A slot the part does not have, at the binding.
    let graph = GRAPH.replace("{ \"out\": \"b\" }", "{ \"output\": \"b\" }");
    let dir = folder(&[("g.ron", &graph), ("parts/tint.ron", TINT)]);
    let found = located_errors(&dir.path().join("g.ron"));
    assert!(
        matches!(&found[0].1, ErrorKind::PartNoSlot { slot, side: "gives", known, .. }
            if slot == "output" && known == "out"),
        "{found:?}"
    );
}

#[test]
fn a_part_needing_a_feature_the_graph_lacks_names_both_places() {
    let graph = GRAPH
        .replace("features: [\"tinted\"],", "")
        .replace("when: \"tinted\", ", "");
    let dir = folder(&[("g.ron", &graph), ("parts/tint.ron", TINT)]);
    let path = dir.path().join("g.ron");
    let found = located_errors(&path);
    assert_eq!(found[0].0, format!("{}:9:16", path.display()), "{found:?}");
    let part = dir.path().join("parts/tint.ron");
    assert!(
        matches!(&found[0].1, ErrorKind::PartFeature { feature, at, declared, .. }
            if feature == "tinted" && declared == "none"
                && at.to_string() == format!("{}:5:16", part.display())),
        "{found:?}"
    );
}

#[test]
fn parts_that_use_each_other_are_a_cycle() {
    let a = r#"Part(takes: { "x": Any }, passes: [(part: "b.ron", inputs: { "x": "x" })])"#;
    let b = r#"Part(takes: { "x": Any }, passes: [(part: "a.ron", inputs: { "x": "x" })])"#;
    let graph = r#"Graph(
    resources: { "t": Texture(format: "rgba8unorm") },
    passes: [(name: "t", plugin: "clear", outputs: { "target": "t" }), (part: "parts/a.ron", inputs: { "x": "t" })],
    outputs: ["t"],
)"#;
    let dir = folder(&[("g.ron", graph), ("parts/a.ron", a), ("parts/b.ron", b)]);
    let found = located_errors(&dir.path().join("g.ron"));
    assert_eq!(found.len(), 1, "{found:?}");
    // At the use that closes the cycle, in b.ron.
    let parts = dir.path().join("parts");
    assert_eq!(
        found[0].0,
        format!("{}:1:43", parts.join("b.ron").display())
    );
    assert_eq!(
        found[0].1.to_string(),
        format!(
            "parts use each other in a cycle: {a} uses {b} uses {a} (the cycle's first use is \
             at {g}:3:79)",
            a = parts.join("a.ron").display(),
            b = parts.join("b.ron").display(),
            g = dir.path().join("g.ron").display()
        )
    );
}

#[test]
fn a_use_of_a_graph_file_or_of_a_file_outside_the_folders_is_refused() {
    let graph = GRAPH.replace("parts/tint.ron", "other.ron");
    let dir = folder(&[("g.ron", &graph), ("other.ron", GRAPH)]);
    let found = located_errors(&dir.path().join("g.ron"));
    assert!(
        matches!(
            &found[0].1,
            ErrorKind::NotAPart {
                kind: "a graph file",
                ..
            }
        ),
        "{found:?}"
    );
    let graph = GRAPH.replace("parts/tint.ron", "../../etc/passwd");
    let dir = folder(&[("g.ron", &graph)]);
    let found = located_errors(&dir.path().join("g.ron"));
    assert!(
        matches!(
            &found[0].1,
            ErrorKind::Reference {
                what: "the part",
                ..
            }
        ),
        "{found:?}"
    );
}

#[test]
fn a_part_checks_on_its_own_with_placeholders_for_what_it_takes() {
    let dir = folder(&[("parts/tint.ron", TINT)]);
    let plan = plan(&dir.path().join("parts/tint.ron"), &["tinted"]);
    let names: Vec<&str> = plan.passes.iter().map(|p| p.name.as_str()).collect();
    // The placeholder for what it takes is an import, which the engine sees: clearing
    // it is kept.
    assert_eq!(names, ["clear", "scratch", "copy"]);
    // Its passes are the file's own: explain names no part they came from.
    assert!(plan.passes.iter().all(|p| p.origin.is_none()));
    // A mistake inside is placed in the part.
    let broken = TINT.replace("\"blit\"", "\"blitz\"");
    let dir = folder(&[("parts/tint.ron", &broken)]);
    let path = dir.path().join("parts/tint.ron");
    let found = located_errors(&path);
    assert_eq!(found[0].0, format!("{}:14:32", path.display()), "{found:?}");
}

#[test]
fn a_preset_adds_a_part_after_a_pass_removes_passes_and_rebinds_outputs() {
    let base = r#"Graph(
    features: ["tinted"],
    resources: { "a": Texture(format: "rgba8unorm"), "c": Texture(format: "rgba8unorm") },
    passes: [
        (name: "clear a", plugin: "clear", outputs: { "target": "a" }),
        (name: "clear c", plugin: "clear", outputs: { "target": "c" }),
    ],
    outputs: ["a", "c"],
)"#;
    let preset = r#"Preset(
    base: "base.ron",
    remove: ["clear c"],
    resources: { "d": Texture(format: "rgba8unorm") },
    after: { "clear a": [(part: "parts/tint.ron", inputs: { "base": "a" }, outputs: { "out": "b" })] },
    passes: { "clear a": (outputs: { "target": "a" }) },
    outputs: ["b"],
)"#;
    let by_hand = r#"Graph(
    features: ["tinted"],
    resources: {
        "a": Texture(format: "rgba8unorm"),
        "c": Texture(format: "rgba8unorm"),
        "scratch": Texture(format: "rgba8unorm"),
        "b": Texture(format: "rgba8unorm"),
        "d": Texture(format: "rgba8unorm"),
    },
    passes: [
        (name: "clear a", plugin: "clear", outputs: { "target": "a" }),
        (name: "clear", plugin: "clear", when: "tinted",
         inputs: { "target": "a" }, outputs: { "target": "cleared" }),
        (name: "scratch", plugin: "clear", outputs: { "target": "scratch" }),
        (name: "copy", plugin: "blit", inputs: { "src": "scratch" }, outputs: { "dst": "b" }),
    ],
    outputs: ["b"],
)"#;
    let dir = folder(&[
        ("base.ron", base),
        ("p.ron", preset),
        ("hand.ron", by_hand),
        ("parts/tint.ron", TINT),
    ]);
    let used = plan(&dir.path().join("p.ron"), &["tinted"]);
    assert_eq!(
        written_out(&used),
        written_out(&plan(&dir.path().join("hand.ron"), &["tinted"]))
    );

    // Adding after a pass the base lacks names the base's passes.
    let wrong = preset.replace("after: { \"clear a\"", "after: { \"clear b\"");
    std::fs::write(dir.path().join("p.ron"), wrong).unwrap();
    let found = located_errors(&dir.path().join("p.ron"));
    assert!(
        matches!(&found[0].1, ErrorKind::UnknownPresetPass { pass, known, .. }
            if pass == "clear b" && known == "clear a"),
        "{found:?}"
    );
}

#[test]
fn a_use_gives_the_part_s_parameters_values_of_its_own() {
    let part = r#"Part(
    gives: { "target": Any },
    resources: { "target": Texture(format: "rgba8unorm", samples: Param(name: "n", default: 1)) },
    passes: [(name: "clear", plugin: "clear", outputs: { "target": "target" })],
)"#;
    let graph = r#"Graph(
    passes: [
        (part: "parts/p.ron", prefix: "four ", values: { "n": 4 }),
        (part: "parts/p.ron", prefix: "one "),
    ],
    outputs: ["four target", "one target"],
)"#;
    let dir = folder(&[("g.ron", graph), ("parts/p.ron", part)]);
    let text = explain::text(&plan(&dir.path().join("g.ron"), &[]));
    assert!(
        text.contains("four target exported: rgba8unorm 1920x1080 4x MSAA\n"),
        "{text}"
    );
    assert!(
        text.contains("one target exported: rgba8unorm 1920x1080\n"),
        "{text}"
    );

    // A value for a parameter the part does not use, at the use's value.
    let wrong = graph.replace("values: { \"n\": 4 }", "values: { \"m\": 4 }");
    let dir = folder(&[("g.ron", &wrong), ("parts/p.ron", part)]);
    let path = dir.path().join("g.ron");
    let found = located_errors(&path);
    assert_eq!(found[0].0, format!("{}:3:58", path.display()), "{found:?}");
    assert!(
        matches!(&found[0].1, ErrorKind::PartParam { name, declared, .. }
            if name == "m" && declared == "n"),
        "{found:?}"
    );
}

#[test]
fn a_use_s_own_condition_is_checked_where_the_use_writes_it() {
    // A feature the graph lacks, in the use's condition, joined inside the part to the
    // clear's own "tinted": the error is the use's, at the feature.
    let graph = GRAPH.replace("when: \"tinted\", ", "when: \"tinted & blnd\", ");
    let dir = folder(&[("g.ron", &graph), ("parts/tint.ron", TINT)]);
    let path = dir.path().join("g.ron");
    let found = located_errors(&path);
    assert_eq!(found.len(), 1, "{found:?}");
    assert_eq!(found[0].0, format!("{}:9:50", path.display()));
    assert!(
        matches!(&found[0].1, ErrorKind::UseFeature { feature, .. } if feature == "blnd"),
        "{found:?}"
    );
    // One that does not parse.
    let graph = GRAPH.replace("when: \"tinted\", ", "when: \"tinted &\", ");
    let dir = folder(&[("g.ron", &graph), ("parts/tint.ron", TINT)]);
    let path = dir.path().join("g.ron");
    let found = located_errors(&path);
    assert!(
        found[0].0.starts_with(&format!("{}:9:", path.display())),
        "{found:?}"
    );
    assert!(
        matches!(&found[0].1, ErrorKind::BadCondition { .. }),
        "{found:?}"
    );
}
