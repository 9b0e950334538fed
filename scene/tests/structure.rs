//! rgraph-scene's structure: analysis sits above the scene model and its loaders, nothing
//! in the model reads the analysis, and no files import each other in a loop. The check is
//! rgraph-core's (graph-core/tests/structure_check.rs, shared).

use std::path::Path;

use crate::structure_check::{check, edges, sources, Layers};

/// rgraph-scene's top-level modules, bottom layer first. A module may import from its own
/// layer and the layers below; within a layer, files must not import each other in a
/// loop. `lib.rs`, the crate's face, is not checked.
const LAYERS: Layers<'_> = &[
    // The scene model and its sources: glTF files, the built-in scenes, the default
    // lighting and its prefiltered environment.
    (
        "scene",
        &[
            "animation",
            "assets",
            "bounds",
            "builder",
            "camera",
            "clusters",
            "deform",
            "environment",
            "error",
            "gltf_loader",
            "light",
            "lighting",
            "material",
            "material_layers",
            "mesh",
            "mips",
            "model",
            "node_tree",
            "normals",
            "particles",
            "points_lines",
            "prefilter",
            "procedural",
            "sheen",
            "stats",
            "tangents",
            "texture",
            "texture_table",
        ],
    ),
    // What a scene needs from a pipeline, measured on the CPU.
    ("analysis", &["analysis"]),
];

#[test]
fn rgraph_scene_imports_run_down_the_layers_without_cycles() {
    let files = sources(&Path::new(env!("CARGO_MANIFEST_DIR")).join("src"));
    let edges = edges(&files);
    for (from, to) in [
        ("analysis/features.rs", "model.rs"),
        ("gltf_loader/mod.rs", "model.rs"),
    ] {
        let edge = (from.to_owned(), to.to_owned());
        assert!(edges.contains(&edge), "{edge:?} not seen");
    }
    let report = check(&files, LAYERS);
    assert!(
        report.is_empty(),
        "rgraph-scene's structure (scene/tests/structure.rs):\n{}",
        report.join("\n")
    );
}

/// The workspace's crates depend one way: the command line on rgraph-passes, on
/// rgraph-scene, on rgraph-core. Cargo refuses a cycle between them; this keeps the order,
/// so that the scene never learns of passes and the graph of neither.
#[test]
fn the_crates_depend_one_way() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let below: [(&str, &[&str]); 2] = [
        ("graph-core/Cargo.toml", &["rgraph-scene", "rgraph-passes"]),
        ("scene/Cargo.toml", &["rgraph-passes"]),
    ];
    for (manifest, above) in below {
        let text = std::fs::read_to_string(root.join(manifest)).unwrap();
        for crate_ in above {
            let line = text.lines().find(|l| l.trim_start().starts_with(crate_));
            assert!(
                line.is_none(),
                "{manifest} depends on {crate_}, a crate above it: {line:?}"
            );
        }
    }
}
