//! rgraph-core's structure: its modules import in one direction, from the layers of
//! [`LAYERS`] down, and no files import each other in a loop (the check is
//! structure_check.rs, which rgraph-scene's and rgraph-passes' tests share).

use std::collections::BTreeMap;
use std::path::Path;

use crate::structure_check::{check, edges, sources, Layers};

/// rgraph-core's top-level modules, bottom layer first. A module may import from its own
/// layer and the layers below; within a layer, files must not import each other in a
/// loop. `lib.rs`, the crate's face, declares and re-exports them all and is not checked.
const LAYERS: Layers<'_> = &[
    // Words every layer uses: handles, access roles, resource descriptions, formats,
    // conditions, errors, device profiles, text positions, reading files.
    (
        "vocabulary",
        &[
            "access",
            "bounded_read",
            "condition",
            "embedded",
            "error",
            "folders",
            "handle",
            "position",
            "profile",
            "resource",
        ],
    ),
    // The declared graph and its plan: passes, their record callbacks and what those see,
    // the builder, the graph, the plan as data.
    (
        "model",
        &["builder", "graph", "pass", "plan", "record", "synthetic"],
    ),
    // Everything that checks without a GPU: compiling graphs, binding them to their plans,
    // caching and explaining plans, reflecting shaders.
    (
        "compile",
        &["compile", "compiled", "explain", "plan_cache", "shader"],
    ),
    // Graph files and the plugins they name.
    ("front-end", &["file", "plugins"]),
    // Devices, the executor, its pool, imports and readback.
    ("execution", &["gpu"]),
];

#[test]
fn graph_core_imports_run_down_the_layers_without_cycles() {
    let files = sources(&Path::new(env!("CARGO_MANIFEST_DIR")).join("src"));
    // The check sees imports through `use`, inline paths and re-exports.
    let edges = edges(&files);
    for (from, to) in [
        ("gpu/executor.rs", "compiled.rs"),
        ("gpu/executor.rs", "gpu/readback.rs"),
        ("file/loaded.rs", "plan_cache.rs"),
        ("compile/mod.rs", "compile/cull.rs"),
        ("plugins/draw.rs", "record.rs"),
    ] {
        let edge = (from.to_owned(), to.to_owned());
        assert!(edges.contains(&edge), "{edge:?} not seen");
    }
    let problems = check(&files, LAYERS);
    assert!(
        problems.is_empty(),
        "rgraph-core's structure (graph-core/tests/structure.rs):\n{}",
        problems.join("\n")
    );
}

#[test]
fn the_check_finds_an_upward_import_and_a_cycle() {
    let files: BTreeMap<String, String> = [
        ("lib.rs", "mod low; mod high; pub use high::Top;"),
        ("low/mod.rs", "mod a; mod b; pub use a::A;"),
        (
            "low/a.rs",
            "use super::b::B; // crate::high is only named here\npub struct A(B);",
        ),
        ("low/b.rs", "pub struct B(Box<crate::low::A>, crate::Top);"),
        ("high.rs", "pub struct Top;"),
    ]
    .into_iter()
    .map(|(path, text)| (path.to_string(), text.to_string()))
    .collect();
    let layers: Layers<'_> = &[("low", &["low"]), ("high", &["high"])];
    assert_eq!(
        check(&files, layers),
        [
            "low/b.rs (layer low) imports crate::Top from high.rs (layer high)",
            "cycle: low/a.rs -> low/b.rs -> low/a.rs",
        ]
    );
}
