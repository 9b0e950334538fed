//! rgraph-scene's structure: analysis sits above the scene model and its loaders, nothing
//! in the model reads the analysis, and no files import each other in a loop. The check is
//! graph-core's (graph-core/tests/structure_check.rs, shared).

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
            "assets", "bounds", "builder", "camera", "environment", "error", "gltf_loader",
            "light", "lighting", "material", "mesh", "mips", "model", "normals",
            "particles", "prefilter", "procedural", "stats", "tangents", "texture",
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
