//! rgraph-passes' structure: its modules import in one direction, from the layers
//! of [`LAYERS`] down, and no files import each other in a loop. The check is rgraph-core's
//! (graph-core/tests/structure_check.rs, shared); code behind feature `gpu` counts, so
//! each pass's recording, beside its declaration in `passes/`, is held to the same rules.

use std::path::Path;

use crate::structure_check::{check, edges, sources, Layers};

/// rgraph-passes' top-level modules, bottom layer first. A module may import from
/// its own layer and the layers below; within a layer, files must not import each other
/// in a loop. `lib.rs`, the crate's face, is not checked.
const LAYERS: Layers<'_> = &[
    // What the host application hands the plugins: the scene (rgraph-scene's), the
    // overrides (the shadow settings among them) and the frame inputs.
    ("host", &["host", "shadows"]),
    // Which shader variants a scene's features need, and which material layers a
    // G-buffer stores in targets of their own.
    ("variant", &["variant", "layers"]),
    // Layouts, shader modules and pipelines kept per device by their description, for
    // every graph recorded on it (feature `gpu`).
    ("kept", &["kept"]),
    // The scene on the device (feature `gpu`).
    ("gpu_scene", &["gpu_scene"]),
    // What the passes share and no pass: `Shared` and `Recording`, slot textures, the
    // depth rule, edge detection, the full-screen draw, the device helpers under
    // `common/gpu` (pipelines, bindings, input-pass state, scene draws), the WGSL.
    ("shared helpers", &["common", "shaders"]),
    // What tools ask of a plan through the shared helpers' slot names: whether it moves
    // a deformed scene's G-buffer points without their pose offset.
    ("plan queries", &["pose"]),
    // One module per pass: parameters, slots, `Plugin::setup` and its recording.
    ("passes", &["passes"]),
    // The plugins by name: what graph files and `register` see.
    ("registry", &["plugins"]),
];

#[test]
fn rgraph_passes_imports_run_down_the_layers_without_cycles() {
    let files = sources(&Path::new(env!("CARGO_MANIFEST_DIR")).join("src"));
    // The check sees imports through `use`, inline paths, re-exports, and the `mod gpu`
    // of a pass.
    let edges = edges(&files);
    for (from, to) in [
        ("plugins.rs", "passes/gbuffer.rs"),
        ("passes/light.rs", "common/gpu/input_pass.rs"),
        ("passes/light.rs", "common/gpu/mod.rs"),
        ("passes/transparent.rs", "passes/forward.rs"),
        ("common/fullscreen.rs", "common/gpu/pipeline.rs"),
        ("common/gpu/bindings.rs", "common/textures.rs"),
        ("gpu_scene/mod.rs", "variant.rs"),
    ] {
        let edge = (from.to_owned(), to.to_owned());
        assert!(edges.contains(&edge), "{edge:?} not seen");
    }
    let report = check(&files, LAYERS);
    assert!(
        report.is_empty(),
        "rgraph-passes' structure (passes/tests/structure.rs):\n{}",
        report.join("\n")
    );
}
