//! The naming rules of graph files: each name is one version with one writer, version
//! names of modified resources are new, passes are ordered by what they read. Each
//! violation is reported where it is written, naming the passes and resources involved.

use crate::ron_support;

use rgraph_core::file::{load_str, ErrorKind, Registry};
use rgraph_core::{CompileOptions, GraphError};
use ron_support::{assert_error, compile_str, only_error};

const PATH: &str = "tests/fixtures/inline.ron";

#[test]
fn two_writers_of_one_name_are_reported_at_the_second() {
    let error = only_error(compile_str(
        r#"Graph(
resources: { "hdr": Texture(format: "rgba16float") },
passes: [
    (name: "a", plugin: "clear", outputs: { "target": "hdr" }),
    (name: "b", plugin: "clear", outputs: { "target": "hdr" }),
],
outputs: ["hdr"],
)"#,
    ));
    assert!(matches!(error.kind, ErrorKind::TwoWriters { .. }));
    assert_error(&error, PATH, 5, 55, &["a", "b", "hdr"]);
}

#[test]
fn writing_an_undeclared_name_is_an_error() {
    let error = only_error(compile_str(
        r#"Graph(
resources: { "hdr": Texture(format: "rgba16float") },
passes: [
    (name: "a", plugin: "clear", outputs: { "target": "hrd" }),
],
)"#,
    ));
    assert_eq!(
        error.to_string(),
        format!(
            "{PATH}:4:55: error: pass \"a\" writes \"hrd\", which is not declared in resources"
        )
    );
}

#[test]
fn a_modified_version_needs_a_new_name() {
    let error = only_error(compile_str(
        r#"Graph(
resources: { "hdr": Texture(format: "rgba16float"), "other": Texture(format: "rgba16float") },
passes: [
    (name: "a", plugin: "clear", outputs: { "target": "hdr" }),
    (name: "b", plugin: "clear", inputs: { "target": "hdr" }, outputs: { "target": "other" }),
],
outputs: ["other"],
)"#,
    ));
    assert!(matches!(error.kind, ErrorKind::VersionNameTaken { .. }));
    assert_error(&error, PATH, 5, 84, &["b", "other"]);
}

#[test]
fn two_passes_modifying_one_version_are_reported_at_the_second() {
    let error = only_error(compile_str(
        r#"Graph(
resources: { "hdr": Texture(format: "rgba16float") },
passes: [
    (name: "a", plugin: "clear", outputs: { "target": "hdr" }),
    (name: "b", plugin: "clear", inputs: { "target": "hdr" }, outputs: { "target": "hdr_b" }),
    (name: "c", plugin: "clear", inputs: { "target": "hdr" }, outputs: { "target": "hdr_c" }),
],
outputs: ["hdr_b", "hdr_c"],
)"#,
    ));
    assert!(matches!(error.kind, ErrorKind::ModifiedTwice { .. }));
    assert_error(&error, PATH, 6, 54, &["b", "c", "hdr"]);
}

#[test]
fn a_pass_reading_what_it_writes_is_an_error() {
    let error = only_error(compile_str(
        r#"Graph(
resources: { "hdr": Texture(format: "rgba16float") },
passes: [
    (name: "a", plugin: "clear", inputs: { "target": "hdr" }, outputs: { "target": "hdr" }),
],
outputs: ["hdr"],
)"#,
    ));
    assert!(matches!(error.kind, ErrorKind::SelfModify { .. }));
    assert_error(&error, PATH, 4, 54, &["a", "hdr"]);
}

#[test]
fn outputs_must_be_written_and_final() {
    let result = compile_str(
        r#"Graph(
resources: { "hdr": Texture(format: "rgba16float"), "unused": Texture(format: "rgba8unorm") },
passes: [
    (name: "a", plugin: "clear", outputs: { "target": "hdr" }),
    (name: "b", plugin: "clear", inputs: { "target": "hdr" }, outputs: { "target": "hdr_b" }),
],
outputs: ["hdr", "unused"],
)"#,
    );
    let errors = result.expect_err("two errors").0;
    assert_eq!(errors.len(), 2, "{errors:#?}");
    assert!(matches!(errors[0].kind, ErrorKind::OutputNotFinal { .. }));
    assert_error(&errors[0], PATH, 7, 11, &["hdr", "b", "hdr_b"]);
    assert!(matches!(errors[1].kind, ErrorKind::UnwrittenOutput { .. }));
    assert_error(&errors[1], PATH, 7, 18, &["unused"]);
}

#[test]
fn duplicate_resources_passes_and_slots_are_errors() {
    let result = compile_str(
        r#"Graph(
resources: { "hdr": Texture(format: "rgba16float"), "hdr": Texture(format: "rgba8unorm") },
passes: [
    (name: "a", plugin: "copy", inputs: { "src": "x", "src": "y" }, outputs: { "dst": "hdr" }),
    (name: "a", plugin: "clear", outputs: { "target": "hdr" }),
],
)"#,
    );
    let kinds: Vec<_> = result
        .expect_err("errors")
        .0
        .into_iter()
        .map(|e| e.kind)
        .collect();
    assert!(
        matches!(kinds[0], ErrorKind::DuplicateResource { .. }),
        "{kinds:#?}"
    );
    assert!(kinds
        .iter()
        .any(|k| matches!(k, ErrorKind::DuplicateSlot { .. })));
    assert!(kinds
        .iter()
        .any(|k| matches!(k, ErrorKind::DuplicatePass { .. })));
}

#[test]
fn every_error_is_reported_in_file_order() {
    let result = compile_str(
        r#"Graph(
resources: { "hdr": Texture(format: "rgba16float") },
passes: [
    (name: "a", plugin: "nope", outputs: { "target": "hdr" }),
    (name: "b", plugin: "blit", inputs: { "src": "missing" }, outputs: { "dst": "hdr2" }),
],
)"#,
    );
    let lines: Vec<String> = result
        .expect_err("errors")
        .0
        .iter()
        .map(|e| e.to_string())
        .collect();
    assert_eq!(lines.len(), 3, "{lines:#?}");
    assert!(lines[0].starts_with(&format!(
        "{PATH}:4:25: error: pass \"a\" uses plugin \"nope\""
    )));
    assert!(lines[1].starts_with(&format!("{PATH}:5:50: error: pass \"b\" reads \"missing\"")));
    assert!(lines[2].starts_with(&format!("{PATH}:5:81: error: pass \"b\" writes \"hdr2\"")));
}

#[test]
fn passes_may_be_listed_in_any_order() {
    let in_order = r#"Graph(
resources: { "a": Texture(format: "rgba8unorm"), "b": Texture(format: "rgba8unorm") },
passes: [
    (name: "first", plugin: "clear", outputs: { "target": "a" }),
    (name: "second", plugin: "copy", inputs: { "src": "a" }, outputs: { "dst": "b" }),
    (name: "third", plugin: "clear", inputs: { "target": "b" }, outputs: { "target": "b2" }),
],
outputs: ["b2"],
)"#;
    let reversed = r#"Graph(
resources: { "a": Texture(format: "rgba8unorm"), "b": Texture(format: "rgba8unorm") },
passes: [
    (name: "third", plugin: "clear", inputs: { "target": "b" }, outputs: { "target": "b2" }),
    (name: "second", plugin: "copy", inputs: { "src": "a" }, outputs: { "dst": "b" }),
    (name: "first", plugin: "clear", outputs: { "target": "a" }),
],
outputs: ["b2"],
)"#;
    let json = |text| serde_json::to_value(compile_str(text).unwrap_or_else(|e| panic!("{e}")));
    assert_eq!(json(in_order).unwrap(), json(reversed).unwrap());
}

#[test]
fn names_denote_the_handles_of_their_versions() {
    let loaded = load_str(
        PATH,
        r#"Graph(
resources: {
    "hdr": Texture(format: "rgba16float"),
    "target": ImportedTexture(format: "rgba16float"),
},
passes: [
    (name: "a", plugin: "clear", outputs: { "target": "hdr" }),
    (name: "b", plugin: "clear", inputs: { "target": "hdr" }, outputs: { "target": "hdr2" }),
    (name: "c", plugin: "copy", inputs: { "src": "hdr2", "dst": "target" }, outputs: { "dst": "done" }),
],
outputs: ["done"],
)"#,
        &Registry::with_builtins(),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let hdr = loaded.names.texture("hdr").expect("hdr");
    let hdr2 = loaded.names.texture("hdr2").expect("hdr2");
    assert_eq!((hdr.id(), hdr.version() + 1), (hdr2.id(), hdr2.version()));
    let done = loaded.names.texture("done").expect("done");
    assert_eq!(loaded.names.texture("target").map(|t| t.version()), Some(0));
    assert_eq!(
        done.id(),
        loaded.names.texture("target").expect("target").id()
    );
    assert!(loaded.names.buffer("hdr").is_none());
    let plan = loaded
        .compile(&CompileOptions::default())
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(plan.find("target").expect("planned").exported);
}

#[test]
fn a_slot_the_plugin_does_not_take_is_an_error() {
    let error = only_error(compile_str(
        r#"Graph(
resources: { "hdr": Texture(format: "rgba16float"), "x": ImportedTexture(format: "rgba8unorm") },
passes: [
    (name: "a", plugin: "clear", inputs: { "extra": "x" }, outputs: { "target": "hdr" }),
],
outputs: ["hdr"],
)"#,
    ));
    assert!(matches!(error.kind, ErrorKind::UnusedSlot { .. }));
    assert_error(&error, PATH, 4, 53, &["a", "clear", "extra", "x"]);
}

#[test]
fn a_slot_the_plugin_needs_is_named() {
    let error = only_error(compile_str(
        r#"Graph(
resources: { "x": ImportedTexture(format: "rgba8unorm") },
passes: [
    (name: "a", plugin: "copy", inputs: { "src": "x" }),
],
)"#,
    ));
    assert_error(&error, PATH, 4, 12, &["a", "dst"]);
    assert!(
        error
            .to_string()
            .ends_with("needs slot \"dst\" in its outputs"),
        "{error}"
    );
}

#[test]
fn a_slot_of_the_wrong_kind_is_named_with_its_resource() {
    let error = only_error(compile_str(
        r#"Graph(
resources: { "x": ImportedTexture(format: "rgba8unorm"), "buf": Buffer(size: 256) },
passes: [
    (name: "a", plugin: "copy", inputs: { "src": "x" }, outputs: { "dst": "buf" }),
],
outputs: ["buf"],
)"#,
    ));
    assert_error(&error, PATH, 4, 75, &["a", "dst", "buf"]);
    assert!(error
        .to_string()
        .contains("holds buffer \"buf\", but needs a texture"));
}

#[test]
fn compile_errors_point_at_the_slot_naming_the_resource() {
    let error = only_error(compile_str(
        r#"Graph(
resources: { "x": ImportedTexture(format: "rgba8unorm"), "depth": Texture(format: "depth32float") },
passes: [
    (name: "a", plugin: "blit", inputs: { "src": "x" }, outputs: { "dst": "depth" }),
],
outputs: ["depth"],
)"#,
    ));
    assert!(matches!(
        error.kind,
        ErrorKind::Graph(GraphError::FormatRole { .. })
    ));
    assert_error(&error, PATH, 4, 75, &["a", "depth"]);
}
