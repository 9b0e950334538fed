//! Histories without a GPU: a texture carried to the next frame, declared in code
//! (`GraphBuilder::history_texture`) and in files (`History(of: ..)`); the checks that
//! its source is written exactly once per frame and the history never; the plan's edge
//! to the next frame, its pair of textures apart from the pool, and explain's text.

use crate::common::{only_error, plan, tex, CLEAR};
use crate::ron_support::{
    assert_error, compile_str, folder, only_error as only_file_error, registry,
};

use rgraph_core::explain;
use rgraph_core::file::ErrorKind;
use rgraph_core::types::TextureFormat;
use rgraph_core::{GraphBuilder, GraphError, Origin};

/// `counter` reads the previous frame's `count` and writes this frame's; `show` samples
/// it into an output.
fn counter() -> GraphBuilder {
    let mut g = GraphBuilder::new();
    let count = g.create_texture("count", tex(TextureFormat::R32Float));
    let previous = g.history_texture("count_prev", count);
    let shown = g.create_texture("shown", tex(TextureFormat::R32Float));
    let mut pass = g.add_compute_pass("counter");
    pass.sampled(previous);
    let count = pass.storage_write(count);
    let mut show = g.add_render_pass("show");
    show.sampled(count);
    let shown = show.color_output(shown, CLEAR);
    g.export(shown);
    g
}

#[test]
fn a_history_is_the_previous_frame_of_its_source_carried_by_an_edge() {
    let plan = plan(&counter().build());
    let count = plan.find("count").unwrap();
    let previous = plan.find("count_prev").unwrap();
    assert_eq!(previous.origin, Origin::History { of: count.id });
    assert_eq!(
        previous.texture, count.texture,
        "a history has its source's shape"
    );
    assert!(count.exported, "the source is this frame's export");
    let [edge] = plan.history.as_slice() else {
        panic!("one edge to the next frame: {:?}", plan.history);
    };
    assert_eq!(
        (edge.source, edge.history, edge.version),
        (count.id, previous.id, 1)
    );
    assert_eq!(edge.writer, "counter");
    assert_eq!(edge.readers, ["counter"]);
    assert_ne!(plan.fingerprint, 0);
}

#[test]
fn a_history_pair_is_never_shared_with_transient_memory() {
    let plan = plan(&counter().build());
    for name in ["count", "count_prev"] {
        let r = plan.find(name).unwrap();
        assert_eq!(
            r.physical, None,
            "{name} lives in the history's pair, not the pool"
        );
        assert!(plan.textures.iter().all(|t| !t.holds.contains(&r.id)));
    }
    // Two textures of 64x64 r32float, counted with the pool's.
    let shown = plan.find("shown").unwrap().bytes;
    assert_eq!(plan.memory.physical_bytes, shown + 2 * 64 * 64 * 4);
    // Both textures are each role in turn: sampled as the history, written as the source,
    // copied from as the export.
    use rgraph_core::types::TextureUsages as U;
    let usage = plan.history[0].usage;
    assert_eq!(usage, U::TEXTURE_BINDING | U::STORAGE_BINDING | U::COPY_SRC);
}

/// `count` carried as `count_prev`, which "late reader" reads into an output; `write`,
/// declared before it, writes `count` when `written`.
fn late_reader(written: bool) -> GraphBuilder {
    let mut g = GraphBuilder::new();
    let count = g.create_texture("count", tex(TextureFormat::R32Float));
    let previous = g.history_texture("count_prev", count);
    let out = g.create_texture("out", tex(TextureFormat::R32Float));
    if written {
        g.add_compute_pass("write").storage_write(count);
    }
    // Declared after the write, reading only the previous frame's contents.
    let mut late = g.add_compute_pass("late reader");
    late.sampled(previous);
    let out = late.storage_write(out);
    g.export(out);
    g
}

#[test]
fn a_history_may_be_read_after_its_source_is_written_with_no_order_between_them() {
    let plan = plan(&late_reader(true).build());
    let order: Vec<&str> = plan.passes.iter().map(|p| p.name.as_str()).collect();
    assert_eq!(order, ["write", "late reader"]);
    assert_eq!(plan.history[0].readers, ["late reader"]);
}

#[test]
fn a_history_whose_source_no_pass_writes_is_an_error_naming_both() {
    let g = late_reader(false);
    let error = only_error(&g.build());
    assert_eq!(
        error,
        GraphError::HistoryNeverWritten {
            resource: "count_prev".into(),
            of: "count".into()
        }
    );
    assert_eq!(
        error.to_string(),
        "history \"count_prev\" carries \"count\" to the next frame, but no pass writes \
         \"count\"; a history's source is written exactly once per frame"
    );
}

#[test]
fn a_source_modified_after_its_write_is_written_twice() {
    let mut g = GraphBuilder::new();
    let count = g.create_texture("count", tex(TextureFormat::Rgba8Unorm));
    g.history_texture("count_prev", count);
    let count = g.add_render_pass("draw").color_output(count, CLEAR);
    g.add_render_pass("overlay")
        .color_output(count, rgraph_core::ColorLoad::Load);
    let error = only_error(&g.build());
    assert_eq!(
        error,
        GraphError::HistoryWrittenTwice {
            of: "count".into(),
            history: "count_prev".into(),
            first: "draw".into(),
            second: "overlay".into(),
        }
    );
    assert_eq!(error.pass(), Some("overlay"));
}

#[test]
fn writing_a_history_is_an_error_that_says_what_to_write() {
    let mut g = GraphBuilder::new();
    let count = g.create_texture("count", tex(TextureFormat::Rgba8Unorm));
    let previous = g.history_texture("count_prev", count);
    g.add_render_pass("draw").color_output(count, CLEAR);
    g.add_render_pass("scribble").color_output(previous, CLEAR);
    let error = only_error(&g.build());
    assert_eq!(
        error.to_string(),
        "pass \"scribble\" writes \"count_prev\", the previous frame's \"count\", which passes \
         only read; write \"count\" instead, and the next frame reads it as \"count_prev\""
    );
}

#[test]
fn a_history_of_an_import_is_refused() {
    let mut g = GraphBuilder::new();
    let target = g.import_texture("target", tex(TextureFormat::Rgba8Unorm));
    g.history_texture("target_prev", target);
    g.add_render_pass("draw").color_output(target, CLEAR);
    let error = only_error(&g.build());
    assert!(
        matches!(&error, GraphError::HistorySource { resource, of, why }
            if resource == "target_prev" && of == "target" && why.contains("imported")),
        "{error}"
    );
}

#[test]
fn explain_shows_the_edge_to_the_next_frame() {
    let plan = plan(&counter().build());
    let text = explain::text(&plan);
    assert!(
        text.contains(
            "\nto the next frame:\n  count@1 (written by \"counter\") -> next frame's \
             count_prev (read by \"counter\")\n      pair of 2 textures r32float 64x64"
        ),
        "{text}"
    );
    assert!(
        text.contains("  count_prev history of count (the previous frame's): "),
        "{text}"
    );
    assert!(
        text.contains("  count exported, to the next frame as count_prev: "),
        "{text}"
    );
    let dot = explain::dot(&plan);
    assert!(
        dot.contains("\"count@1\" -> \"count_prev@0\" [style=dashed, label=\"next frame\"];"),
        "{dot}"
    );
    let json = explain::json(&plan);
    assert!(json.contains("\"history\": ["), "{json}");
}

/// `fade` blends the previous frame's `accum` into this frame's; `present` shows it.
fn file(accum_writers: &str) -> String {
    format!(
        r#"Graph(
    resources: {{
        "accum": Texture(format: "rgba8unorm", size: Absolute(4, 4)),
        "accum_prev": History(of: "accum"),
        "shown": Texture(format: "rgba8unorm", size: Absolute(4, 4)),
    }},
    passes: [
{accum_writers}
        (name: "present", plugin: "blit", inputs: {{ "src": "accum_prev" }}, outputs: {{ "dst": "shown" }}),
    ],
    outputs: ["shown"],
)"#
    )
}

const FADE: &str = r#"        (name: "fade", plugin: "blit", inputs: { "src": "accum_prev" }, outputs: { "dst": "accum" }),"#;

#[test]
fn a_file_declares_a_history_by_the_texture_it_carries() {
    let plan = compile_str(&file(FADE)).unwrap_or_else(|e| panic!("{e}"));
    let edge = &plan.history[0];
    assert_eq!(plan.resource(edge.source).name, "accum");
    assert_eq!(plan.resource(edge.history).name, "accum_prev");
    assert_eq!(edge.writer, "fade");
    // Reads of the previous frame need no order against the write: both readers may run
    // anywhere, and the file's order stands.
    assert_eq!(edge.readers, ["fade", "present"]);
}

/// The one error compiling `text` gives, a graph error, checked to be at `line`:`column`
/// of the inline file and to name each of `names`.
fn file_error(text: &str, (line, column): (usize, usize), names: &[&str]) -> GraphError {
    let error = only_file_error(compile_str(text));
    assert_error(&error, "tests/fixtures/inline.ron", line, column, names);
    match error.kind {
        ErrorKind::Graph(error) => error,
        kind => panic!("expected a graph error, got {kind}"),
    }
}

#[test]
fn a_file_whose_history_source_no_pass_writes_points_at_the_history() {
    let error = file_error(&file(""), (4, 9), &["accum_prev", "accum"]);
    assert!(
        matches!(error, GraphError::HistoryNeverWritten { .. }),
        "{error}"
    );
}

#[test]
fn a_file_with_two_writers_of_a_history_source_names_both() {
    let two = format!(
        "{FADE}\n        (name: \"fade again\", plugin: \"blit\", inputs: {{ \"src\": \"shown\" }}, \
         outputs: {{ \"dst\": \"accum\" }}),"
    );
    let result = compile_str(&file(&two));
    let errors = match result {
        Ok(_) => panic!("two writers of a history's source compiled"),
        Err(errors) => errors,
    };
    let text = errors.to_string();
    assert!(
        text.contains("\"fade\"") && text.contains("\"fade again\""),
        "{text}"
    );
    assert!(text.contains("\"accum\""), "{text}");
}

#[test]
fn a_file_that_writes_a_history_points_at_the_slot() {
    let scribble = format!(
        "{FADE}\n        (name: \"scribble\", plugin: \"clear\", outputs: {{ \"target\": \"accum_prev\" }}),"
    );
    let names = ["scribble", "accum_prev", "accum"];
    let error = file_error(&file(&scribble), (9, 66), &names);
    assert!(
        matches!(error, GraphError::HistoryWritten { .. }),
        "{error}"
    );
}

#[test]
fn a_file_history_of_an_unknown_name_points_at_it() {
    let text = file(FADE).replace("History(of: \"accum\")", "History(of: \"acum\")");
    let errors = match compile_str(&text) {
        Ok(_) => panic!("a history of an unknown name compiled"),
        Err(errors) => errors,
    };
    let error = &errors.0[0];
    assert!(
        matches!(&error.kind, ErrorKind::Graph(GraphError::HistorySource { why, .. })
            if why == "no resource has that name"),
        "{errors}"
    );
    assert_error(
        error,
        "tests/fixtures/inline.ron",
        4,
        35,
        &["accum_prev", "acum"],
    );
}

/// A part keeps a history of its own: each use's prefix names both sides.
const ECHO: &str = r#"Part(
    takes: { "src": Texture(format: "rgba8unorm") },
    gives: { "out": Texture(format: "rgba8unorm") },
    resources: {
        "echo": Texture(format: "rgba8unorm", size: Absolute(4, 4)),
        "echo_prev": History(of: "echo"),
        "out": Texture(format: "rgba8unorm", size: Absolute(4, 4)),
    },
    passes: [
        (name: "remember", plugin: "blit", inputs: { "src": "src" }, outputs: { "dst": "echo" }),
        (name: "recall", plugin: "blit", inputs: { "src": "echo_prev" }, outputs: { "dst": "out" }),
    ],
)"#;

#[test]
fn each_use_of_a_part_has_a_history_of_its_own() {
    let graph = r#"Graph(
    resources: { "a": Texture(format: "rgba8unorm", size: Absolute(4, 4)) },
    passes: [
        (name: "clear a", plugin: "clear", outputs: { "target": "a" }),
        (part: "parts/echo.ron", prefix: "left ", inputs: { "src": "a" }),
        (part: "parts/echo.ron", prefix: "right ", inputs: { "src": "a" }),
    ],
    outputs: ["left out", "right out"],
)"#;
    let dir = folder(&[("g.ron", graph), ("parts/echo.ron", ECHO)]);
    let loaded = rgraph_core::file::load_file(dir.path().join("g.ron"), &registry())
        .unwrap_or_else(|e| panic!("{e}"));
    let plan = loaded
        .compile(&rgraph_core::CompileOptions::default())
        .unwrap_or_else(|e| panic!("{e}"));
    let mut edges: Vec<(String, String, String)> = plan
        .history
        .iter()
        .map(|e| {
            let name = |id| plan.resource(id).name.clone();
            (name(e.source), name(e.history), e.writer.clone())
        })
        .collect();
    edges.sort();
    assert_eq!(
        edges,
        [
            (
                "left echo".into(),
                "left echo_prev".into(),
                "left remember".into()
            ),
            (
                "right echo".into(),
                "right echo_prev".into(),
                "right remember".into()
            ),
        ]
    );
}

/// [`two_outputs`] compiled with `output` alone kept, as `rgraph render --view` keeps it.
fn two_outputs_keeping(output: &str) -> rgraph_core::Plan {
    let mut graph = two_outputs();
    graph.keep_outputs(&[output]).unwrap();
    graph
        .compile(&rgraph_core::CompileOptions::default())
        .unwrap_or_else(|e| panic!("{e}"))
}

/// [`file`] with `fade`, and a second output "other" that `other` clears.
fn two_outputs() -> rgraph_core::file::LoadedGraph {
    let text = file(FADE)
        .replace(
            r#""shown": Texture(format: "rgba8unorm", size: Absolute(4, 4)),"#,
            r#""shown": Texture(format: "rgba8unorm", size: Absolute(4, 4)),
        "other": Texture(format: "rgba8unorm", size: Absolute(4, 4)),"#,
        )
        .replace(
            r#"    ],
    outputs: ["shown"],"#,
            r#"        (name: "other", plugin: "clear", outputs: { "target": "other" }),
    ],
    outputs: ["shown", "other"],"#,
        );
    rgraph_core::file::load_str("tests/fixtures/inline.ron", &text, &registry())
        .unwrap_or_else(|e| panic!("{e}"))
}

/// Showing one output of several (`rgraph render --view`) culls the passes only the
/// others need: where that is every reader of a history and its source's writer, the
/// history goes with them, its pair not made (it was, without usages, which the device
/// refused: `--view motion` of taa.ron).
#[test]
fn a_history_whose_readers_are_all_culled_has_no_edge_and_no_textures() {
    let plan = two_outputs_keeping("other");
    let order: Vec<&str> = plan.passes.iter().map(|p| p.name.as_str()).collect();
    assert_eq!(order, ["other"]);
    assert!(plan.history.is_empty(), "{:?}", plan.history);
    assert_eq!(plan.fingerprint, 0);
}

/// A history read by a pass that stays keeps its source's writer, though the source is
/// no longer an output: the next frame's read needs this frame's write.
#[test]
fn a_history_read_by_a_live_pass_keeps_its_source_s_writer() {
    let plan = two_outputs_keeping("shown");
    let order: Vec<&str> = plan.passes.iter().map(|p| p.name.as_str()).collect();
    assert_eq!(order, ["fade", "present"]);
    assert_eq!(plan.history[0].writer, "fade");
}
