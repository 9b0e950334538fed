//! Histories without a GPU: a texture carried to the next frame, declared in code
//! (`GraphBuilder::history_texture`); the checks that
//! its source is written exactly once per frame and the history never; the plan's edge
//! to the next frame, its pair of textures apart from the pool, and explain's text.

use crate::common::{only_error, plan, tex, CLEAR};

use rgraph_core::explain;
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

#[test]
fn a_history_may_be_read_after_its_source_is_written_with_no_order_between_them() {
    let mut g = GraphBuilder::new();
    let count = g.create_texture("count", tex(TextureFormat::R32Float));
    let previous = g.history_texture("count_prev", count);
    let out = g.create_texture("out", tex(TextureFormat::R32Float));
    let mut write = g.add_compute_pass("write");
    write.storage_write(count);
    // Declared after the write, reading only the previous frame's contents.
    let mut late = g.add_compute_pass("late reader");
    late.sampled(previous);
    let out = late.storage_write(out);
    g.export(out);
    let plan = plan(&g.build());
    let order: Vec<&str> = plan.passes.iter().map(|p| p.name.as_str()).collect();
    assert_eq!(order, ["write", "late reader"]);
    assert_eq!(plan.history[0].readers, ["late reader"]);
}

#[test]
fn a_history_whose_source_no_pass_writes_is_an_error_naming_both() {
    let mut g = GraphBuilder::new();
    let count = g.create_texture("count", tex(TextureFormat::R32Float));
    let previous = g.history_texture("count_prev", count);
    let out = g.create_texture("out", tex(TextureFormat::R32Float));
    let mut read = g.add_compute_pass("reader");
    read.sampled(previous);
    let out = read.storage_write(out);
    g.export(out);
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
