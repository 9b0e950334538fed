//! Bad conditions in a real pipeline: a misspelt feature in deferred_msaa_4x.ron (in a
//! pass's or resource's `when`, or in a conditional format) is a validation error at the
//! feature's line and column, naming the pass or resource, from the library and from
//! `rgraph validate`. No GPU.

use std::process::Command;

use rgraph_core::file::{load_str, FileErrors, Registry};

const PIPELINE: &str = "pipelines/deferred_msaa_4x.ron";

fn edited(from: &str, to: &str) -> String {
    let path = format!("{}/{PIPELINE}", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(path).expect("the pipeline reads");
    assert_eq!(
        text.matches(from).count(),
        1,
        "{from:?} is in the file once"
    );
    text.replace(from, to)
}

fn load(text: &str) -> FileErrors {
    let mut registry = Registry::with_builtins();
    rgraph_passes::register(&mut registry, None);
    match load_str(PIPELINE, text, &registry) {
        Ok(_) => panic!("expected the edited pipeline to be rejected"),
        Err(errors) => errors,
    }
}

/// `FILE:LINE:COL` of the first `needle` in `text`, plus `skip` characters.
fn at(text: &str, needle: &str, skip: usize) -> String {
    let offset = text.find(needle).expect("the needle is in the text");
    let before = &text[..offset];
    let line = 1 + before.matches('\n').count();
    let column = 1
        + before[before.rfind('\n').map_or(0, |i| i + 1)..]
            .chars()
            .count()
        + skip;
    format!("{PIPELINE}:{line}:{column}")
}

#[test]
fn a_misspelt_feature_in_a_pass_condition_is_an_error_at_the_feature() {
    let text = edited(
        "name: \"light edges\",\n            plugin: \"light_edge\",\n            when: \"!unlit_only & !no_lights\",",
        "name: \"light edges\",\n            plugin: \"light_edge\",\n            when: \"!unlitonly & !no_lights\",",
    );
    let errors = load(&text);
    assert_eq!(
        errors.to_string(),
        format!(
            "{}: error: pass \"light edges\": condition \"!unlitonly & !no_lights\" names feature \"unlitonly\", which the graph does not declare (declared: auto_exposure, background, blend, no_lights, shallow_depth, unlit_only)",
            at(&text, "unlitonly &", 0)
        )
    );
}

#[test]
fn a_misspelt_feature_in_a_resource_condition_is_an_error_at_the_feature() {
    let text = edited(
        "\"material\": Texture(format: \"rgba8unorm\", samples: Param(name: \"msaa\", default: 4), \
         when: \"!unlit_only\")",
        "\"material\": Texture(format: \"rgba8unorm\", samples: Param(name: \"msaa\", default: 4), \
         when: \"!unlit-only\")",
    );
    let errors = load(&text);
    // "unlit-only" is not a name: the condition stops parsing at the '-'.
    assert_eq!(
        errors.to_string(),
        format!(
            "{}: error: resource \"material\": condition \"!unlit-only\": expected a feature name, found '-' after a feature; conditions read `a & !b` (only `&` and `!`)",
            at(&text, "-only\")", 0)
        )
    );
}

#[test]
fn a_misspelt_feature_in_a_conditional_format_is_an_error_at_the_feature() {
    let text = edited(
        "format_if: [(\"shallow_depth\", \"depth24plus-stencil8\")]",
        "format_if: [(\"shallow_dept\", \"depth24plus-stencil8\")]",
    );
    let errors = load(&text);
    assert_eq!(
        errors.to_string(),
        format!(
            "{}: error: resource \"depth\": the condition \"shallow_dept\" of a conditional format names feature \"shallow_dept\", which the graph does not declare (declared: auto_exposure, background, blend, no_lights, shallow_depth, unlit_only)",
            at(&text, "shallow_dept\"", 0)
        )
    );
}

#[test]
fn rgraph_validate_reports_it_with_exit_status_1() {
    let text = edited(
        "when: \"background\",",
        "when: \"background & spot_lights\",",
    );
    let dir = std::env::temp_dir().join(format!("specialise-errors-{}", std::process::id()));
    // The deferred plugins embed their shaders, so the file may live anywhere with the
    // parts it uses beside it.
    let parts = dir.join("parts");
    std::fs::create_dir_all(&parts).unwrap();
    let shipped = format!("{}/pipelines/parts", env!("CARGO_MANIFEST_DIR"));
    for part in std::fs::read_dir(shipped).unwrap() {
        let part = part.unwrap().path();
        std::fs::copy(&part, parts.join(part.file_name().unwrap())).unwrap();
    }
    let path = dir.join("deferred_msaa_4x.ron");
    std::fs::write(&path, &text).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_rgraph"))
        .args(["validate", path.to_str().unwrap()])
        .output()
        .expect("rgraph runs");
    std::fs::remove_dir_all(&dir).unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(1), "{stdout}");
    let column = at(&text, "spot_lights\"", 0);
    let column = column.trim_start_matches(PIPELINE);
    assert!(
        stdout.contains(&format!(
            "deferred_msaa_4x.ron{column}: error: pass \"background\": condition \"background & spot_lights\" names feature \"spot_lights\""
        )),
        "{stdout}"
    );
}
