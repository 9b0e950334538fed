//! Bad conditions in a real pipeline: a misspelt feature in deferred_msaa_4x.ron or the
//! parts it uses (in a pass's or resource's `when`, or in a conditional format) is a
//! validation error at the feature's line and column in the file it is written in, naming
//! the pass or resource, from the library and from `rgraph validate`. No GPU.

use std::path::PathBuf;
use std::process::Command;

use rgraph_core::file::{load_str, FileErrors, Registry};

use crate::common::{edited_pipeline, EditedPipeline};

const PIPELINE: &str = "deferred_msaa_4x.ron";

/// deferred_msaa_4x.ron with `from` (once in the pipeline or one of its parts) replaced
/// by `to`: the edited pipeline, and the path and text of the file edited.
fn edited(from: &str, to: &str) -> (EditedPipeline, PathBuf, String) {
    let copies = edited_pipeline(PIPELINE, &[(from, to)]);
    let (path, text) = copies.edited[0].clone();
    assert_eq!(
        text.matches(to).count(),
        1,
        "{to:?} is in {} once",
        path.display()
    );
    (copies, path, text)
}

fn load(copies: &EditedPipeline) -> FileErrors {
    let mut registry = Registry::with_builtins();
    rgraph_passes::register(&mut registry, None);
    match load_str(&copies.path, &copies.text, &registry) {
        Ok(_) => panic!("expected the edited pipeline to be rejected"),
        Err(errors) => errors,
    }
}

/// `FILE:LINE:COL` of the first `needle` in `text`, the text of the file at `path`.
fn at(path: &std::path::Path, text: &str, needle: &str) -> String {
    let offset = text.find(needle).expect("the needle is in the text");
    let before = &text[..offset];
    let line = 1 + before.matches('\n').count();
    let column = 1 + before[before.rfind('\n').map_or(0, |i| i + 1)..]
        .chars()
        .count();
    format!("{}:{line}:{column}", path.display())
}

#[test]
fn a_misspelt_feature_in_a_pass_condition_is_an_error_at_the_feature() {
    // The edge pass's condition (the light passes' reads the same).
    let (copies, path, text) = edited(
        "plugin: \"edge_stencil\",\n            when: \"!unlit_only & !no_lights\",",
        "plugin: \"edge_stencil\",\n            when: \"!unlitonly & !no_lights\",",
    );
    let errors = load(&copies);
    assert_eq!(
        errors.to_string(),
        format!(
            "{}: error: pass \"edges\": condition \"!unlitonly & !no_lights\" names feature \"unlitonly\", which the graph does not declare (declared: auto_exposure, background, blend, clearcoat, clearcoat_normal, color_bytes_64, no_lights, points_lines, shadows, shallow_depth, sheen, specular, unlit_only)",
            at(&path, &text, "unlitonly &")
        )
    );
}

#[test]
fn a_misspelt_feature_in_a_resource_condition_is_an_error_at_the_feature() {
    let (copies, path, text) = edited(
        "\"transparent\": Texture(format: \"rgba16float\", samples: Param(name: \"msaa\", default: 4), when: \"blend\")",
        "\"transparent\": Texture(format: \"rgba16float\", samples: Param(name: \"msaa\", default: 4), when: \"bl-end\")",
    );
    let errors = load(&copies);
    // "bl-end" is not a name: the condition stops parsing at the '-'.
    assert_eq!(
        errors.to_string(),
        format!(
            "{}: error: resource \"transparent\": condition \"bl-end\": expected a feature name, found '-' after a feature; conditions read `a & !b` (only `&` and `!`)",
            at(&path, &text, "-end\")")
        )
    );
}

#[test]
fn a_misspelt_feature_in_a_conditional_format_is_an_error_at_the_feature() {
    let (copies, path, text) = edited(
        "format_if: [(\"shallow_depth\", \"depth24plus-stencil8\")]",
        "format_if: [(\"shallow_dept\", \"depth24plus-stencil8\")]",
    );
    let errors = load(&copies);
    assert_eq!(
        errors.to_string(),
        format!(
            "{}: error: resource \"depth\": the condition \"shallow_dept\" of a conditional format names feature \"shallow_dept\", which the graph does not declare (declared: auto_exposure, background, blend, clearcoat, clearcoat_normal, color_bytes_64, no_lights, points_lines, shadows, shallow_depth, sheen, specular, unlit_only)",
            at(&path, &text, "shallow_dept\"")
        )
    );
}

#[test]
fn rgraph_validate_reports_it_with_exit_status_1() {
    // The deferred plugins embed their shaders, so the file may live anywhere with the
    // parts it uses beside it.
    let (copies, path, text) = edited(
        "when: \"background\",",
        "when: \"background & spot_lights\",",
    );
    let out = Command::new(env!("CARGO_BIN_EXE_rgraph"))
        .args(["validate", copies.path.to_str().unwrap()])
        .output()
        .expect("rgraph runs");
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(1), "{stdout}");
    assert!(
        stdout.contains(&format!(
            "{}: error: pass \"background\": condition \"background & spot_lights\" names feature \"spot_lights\"",
            at(&path, &text, "spot_lights\"")
        )),
        "{stdout}"
    );
}
