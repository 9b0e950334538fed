//! Bad parameters and slots in the baselines' plugins (`forward`, `gbuffer_resolve`,
//! `light_nonedge`'s `samples`): each is a load error naming the pass, the slot and the
//! resource, never a panic. No GPU: the registry is made without a host, as build.rs
//! makes it.

use std::path::Path;

use rgraph_core::file::{load_str, Registry};

/// Loads `pipeline` from `pipelines/` with `from` replaced by `to`, and returns the
/// error text the load must fail with.
pub fn error(pipeline: &str, from: &str, to: &str) -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("pipelines")
        .join(pipeline);
    let text = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()));
    assert!(text.contains(from), "{pipeline} has no \"{from}\" to edit");
    let mut registry = Registry::with_builtins();
    rgraph_passes::register(&mut registry, None);
    match load_str(&path, &text.replace(from, to), &registry) {
        Ok(_) => panic!("{pipeline} with \"{to}\" loaded, but should not"),
        Err(errors) => {
            let message = errors.to_string();
            println!("{pipeline} with \"{to}\":\n{message}");
            message
        }
    }
}

pub fn assert_names(message: &str, parts: &[&str]) {
    for part in parts {
        assert!(
            message.contains(part),
            "the error does not name {part}:\n{message}"
        );
    }
}

#[test]
fn forward_hdr_with_another_sample_count_than_its_depth() {
    let message = error(
        "forward_msaa_4x.ron",
        r#""hdr": Texture(format: "rgba16float", samples: Param(name: "msaa", default: 4))"#,
        r#""hdr": Texture(format: "rgba16float", samples: 1)"#,
    );
    assert_names(&message, &["forward", "slot \"hdr\"", "1 sample", "4"]);
}

#[test]
fn forward_depth_of_a_color_format() {
    // The whole declaration, whatever depth formats (fallback, conditional ones) the
    // file picks and however many lines it takes: up to the `),` that closes it.
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("pipelines/forward_msaa_4x.ron");
    let text = std::fs::read_to_string(&path).expect("forward_msaa_4x.ron is readable");
    let start = text
        .find("\"depth\": Texture(")
        .expect("forward_msaa_4x.ron declares \"depth\"");
    let end = start + text[start..].find("),\n").expect("the declaration closes") + 2;
    let message = error(
        "forward_msaa_4x.ron",
        &text[start..end],
        r#""depth": Texture(format: "rgba8unorm", samples: 4),"#,
    );
    assert_names(&message, &["slot \"depth\"", "rgba8unorm", "depth24plus"]);
}

#[test]
fn forward_unknown_shading() {
    let message = error("forward_msaa_4x.ron", "shading: pixel", "shading: texel");
    assert_names(&message, &["texel", "pixel", "sample"]);
}

#[test]
fn gbuffer_resolve_output_that_is_multisampled() {
    let message = error(
        "deferred_gbuffer_resolve_4x.ron",
        r#""normal_1x": Texture(format: "rg16float")"#,
        r#""normal_1x": Texture(format: "rg16float", samples: 4)"#,
    );
    assert_names(
        &message,
        &["slot \"resolved_normal\"", "normal_1x", "4 sample"],
    );
}

#[test]
fn gbuffer_resolve_without_its_depth_output() {
    let message = error(
        "deferred_gbuffer_resolve_4x.ron",
        r#""depth": "depth_1x","#,
        "",
    );
    assert_names(&message, &["resolve gbuffer", "\"depth\""]);
}

#[test]
fn light_nonedge_unknown_samples() {
    let message = error(
        "deferred_onthefly_resolve_4x.ron",
        "samples: average",
        "samples: median",
    );
    assert_names(&message, &["median", "first", "average"]);
}
