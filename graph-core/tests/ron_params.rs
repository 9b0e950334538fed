//! Graph-file parameters: `samples: Param(name: "msaa", default: 4)` takes its default, or
//! the value the loader is given; a value for an undeclared parameter, a value of 0 and
//! two defaults for one name are errors at their place in the file. So do a size
//! `Divided(Param(..))` and a `Param(..)` in a pass's plugin parameters.

use rgraph_core::file::{
    declared_params, load_str, load_str_with, ErrorKind, GraphParams, Registry,
};
use rgraph_core::CompileOptions;

/// A color and a depth target cleared, their sample count one parameter (line 3 holds the
/// first use, line 4 the second), and a single-sampled "out".
const MSAA: &str = r#"Graph(
    resources: {
        "color": Texture(format: "rgba8unorm", samples: Param(name: "msaa", default: 4)),
        "depth": Texture(format: "depth32float", samples: Param(name: "msaa", default: 4)),
        "out": Texture(format: "rgba8unorm"),
    },
    passes: [
        (name: "clear", plugin: "clear", outputs: { "target": "color" }),
        (name: "clear depth", plugin: "clear", outputs: { "target": "depth" }),
        (name: "clear out", plugin: "clear", outputs: { "target": "out" }),
    ],
    outputs: ["color", "depth", "out"],
)"#;

const PATH: &str = "tests/fixtures/inline.ron";

fn samples(params: &GraphParams) -> Vec<(String, u32)> {
    let loaded = load_str_with(PATH, MSAA, &Registry::with_builtins(), params)
        .unwrap_or_else(|e| panic!("{e}"));
    loaded
        .graph
        .resources()
        .iter()
        .filter_map(|r| match &r.desc {
            rgraph_core::ResourceDesc::Texture(t) => Some((r.name.clone(), t.samples)),
            rgraph_core::ResourceDesc::Buffer(_) => None,
        })
        .collect()
}

#[test]
fn a_parameter_takes_its_default_or_the_value_given() {
    let pairs = |n| vec![("color".into(), n), ("depth".into(), n), ("out".into(), 1)];
    assert_eq!(samples(&GraphParams::new()), pairs(4));
    assert_eq!(samples(&GraphParams::new().with("msaa", 1)), pairs(1));
    assert_eq!(samples(&GraphParams::new().with("msaa", 8)), pairs(8));

    let loaded = load_str_with(
        PATH,
        MSAA,
        &Registry::with_builtins(),
        &GraphParams::new().with("msaa", 2),
    )
    .unwrap();
    assert_eq!(loaded.params(), &GraphParams::new().with("msaa", 2));
    let defaults = load_str(PATH, MSAA, &Registry::with_builtins()).unwrap();
    assert_eq!(defaults.params(), &GraphParams::new().with("msaa", 4));
}

#[test]
fn a_value_the_device_cannot_take_is_a_compile_error_naming_the_texture() {
    let loaded = load_str_with(
        PATH,
        MSAA,
        &Registry::with_builtins(),
        &GraphParams::new().with("msaa", 3),
    )
    .unwrap();
    let errors = loaded.compile(&CompileOptions::default()).unwrap_err();
    assert!(errors.to_string().contains("\"color\""), "{errors}");
}

#[test]
fn a_value_for_an_undeclared_parameter_is_an_error_listing_the_declared_ones() {
    let params = GraphParams::new().with("samples", 8);
    let errors = load_str_with(PATH, MSAA, &Registry::with_builtins(), &params)
        .err()
        .expect("rejected");
    assert_eq!(errors.0.len(), 1, "{errors}");
    assert!(matches!(errors.0[0].kind, ErrorKind::UnknownParam { .. }));
    assert_eq!(
        errors.to_string().trim_end(),
        "tests/fixtures/inline.ron:1:1: error: parameter \"samples\" is given a value (8), \
         but the file declares no parameter of that name (it declares: msaa)"
    );
}

#[test]
fn a_zero_value_is_an_error_at_each_use() {
    let params = GraphParams::new().with("msaa", 0);
    let errors = load_str_with(PATH, MSAA, &Registry::with_builtins(), &params)
        .err()
        .expect("rejected");
    let lines: Vec<String> = errors.0.iter().map(|e| e.to_string()).collect();
    assert_eq!(
        lines,
        [
            "tests/fixtures/inline.ron:3:69: error: parameter \"msaa\" is 0, but the samples of \
             \"color\" must be 1 or more",
            "tests/fixtures/inline.ron:4:71: error: parameter \"msaa\" is 0, but the samples of \
             \"depth\" must be 1 or more",
        ]
    );
}

#[test]
fn two_defaults_for_one_parameter_are_an_error_at_the_second() {
    let text = MSAA.replace(
        "\"depth32float\", samples: Param(name: \"msaa\", default: 4)",
        "\"depth32float\", samples: Param(name: \"msaa\", default: 2)",
    );
    let errors = load_str(PATH, &text, &Registry::with_builtins())
        .err()
        .expect("rejected");
    assert_eq!(
        errors.to_string().trim_end(),
        "tests/fixtures/inline.ron:4:71: error: parameter \"msaa\" has default 4 where it is \
         first used and 2 here; give every use the same default"
    );
}

#[test]
fn a_misspelt_parameter_is_a_syntax_error_at_the_count() {
    let text = MSAA.replacen("Param(name: \"msaa\"", "Param(nme: \"msaa\"", 1);
    let errors = load_str(PATH, &text, &Registry::with_builtins())
        .err()
        .expect("rejected");
    assert!(
        matches!(errors.0[0].kind, ErrorKind::Syntax { .. }),
        "{errors}"
    );
    assert!(
        errors
            .to_string()
            .starts_with("tests/fixtures/inline.ron:3:"),
        "{errors}"
    );
}

#[test]
fn the_declared_parameters_are_read_without_declaring() {
    let path = std::env::temp_dir().join(format!("rgraph-params-{}.ron", std::process::id()));
    std::fs::write(&path, MSAA).unwrap();
    let declared = declared_params(&path, &Registry::new());
    std::fs::remove_file(&path).unwrap();
    assert_eq!(declared.unwrap(), GraphParams::new().with("msaa", 4));
}

/// A target at a parameter's fraction of the output, and a depth-stencil cleared to a
/// stencil value that is a parameter of the clear plugin (line 8).
const DIVIDED: &str = r#"Graph(
    resources: {
        "small": Texture(format: "rgba8unorm", size: Divided(Param(name: "scale", default: 2))),
        "third": Texture(format: "rgba8unorm", size: Divided(3)),
        "depth": Texture(format: "depth24plus-stencil8"),
    },
    passes: [
        (name: "clear", plugin: "clear", outputs: { "target": "small" }),
        (name: "mark", plugin: "clear", params: (stencil: Param(name: "mark", default: 7), depth: 0.5),
         outputs: { "target": "depth" }),
        (name: "clear third", plugin: "clear", outputs: { "target": "third" }),
    ],
    outputs: ["small", "depth", "third"],
)"#;

fn divided(params: &GraphParams) -> (Vec<rgraph_core::Size>, u32) {
    let loaded = load_str_with(PATH, DIVIDED, &Registry::with_builtins(), params)
        .unwrap_or_else(|e| panic!("{e}"));
    let sizes = loaded
        .graph
        .resources()
        .iter()
        .filter_map(|r| match &r.desc {
            rgraph_core::ResourceDesc::Texture(t) => Some(t.size),
            rgraph_core::ResourceDesc::Buffer(_) => None,
        })
        .collect();
    let stencil = loaded.graph.passes()[1]
        .accesses
        .iter()
        .find_map(|a| match a.role {
            rgraph_core::Role::Texture(rgraph_core::TextureRole::DepthStencil {
                stencil: rgraph_core::AspectAccess::Clear(v),
                ..
            }) => Some(v),
            _ => None,
        })
        .expect("the mark pass clears the stencil");
    (sizes, stencil)
}

#[test]
fn a_size_divided_by_a_parameter_and_a_plugin_parameter_take_their_values() {
    use rgraph_core::Size::Relative;
    let (sizes, stencil) = divided(&GraphParams::new());
    assert_eq!(sizes, [Relative(0.5), Relative(1.0 / 3.0), Relative(1.0)]);
    assert_eq!(stencil, 7);
    let given = GraphParams::new().with("scale", 4).with("mark", 0x80);
    let (sizes, stencil) = divided(&given);
    assert_eq!(sizes[0], Relative(0.25));
    assert_eq!(stencil, 0x80);
    let loaded = load_str(PATH, DIVIDED, &Registry::with_builtins()).unwrap();
    assert_eq!(
        loaded.params(),
        &GraphParams::new().with("mark", 7).with("scale", 2)
    );
    let plan = loaded
        .compile(&CompileOptions {
            output_size: (640, 360),
            ..Default::default()
        })
        .unwrap_or_else(|e| panic!("{e}"));
    let text = rgraph_core::explain::text(&plan);
    assert!(text.contains("320x180"), "{text}");
    assert!(text.contains("213x120"), "{text}");
}

#[test]
fn a_zero_divisor_is_an_error_at_its_use_and_a_plugin_judges_its_own_values() {
    let errors = load_str_with(
        PATH,
        DIVIDED,
        &Registry::with_builtins(),
        &GraphParams::new().with("scale", 0),
    )
    .err()
    .expect("rejected");
    assert_eq!(
        errors.to_string().trim_end(),
        "tests/fixtures/inline.ron:3:74: error: parameter \"scale\" is 0, but the size \
         divisor of \"small\" must be 1 or more"
    );
    // The clear plugin takes any stencil value, 0 included.
    divided(&GraphParams::new().with("mark", 0));
}

#[test]
fn plugin_errors_after_a_parameter_keep_their_columns() {
    let text = DIVIDED.replace("depth: 0.5)", "dpth: 0.5)");
    let errors = load_str(PATH, &text, &Registry::with_builtins())
        .err()
        .expect("rejected");
    let line = errors.to_string();
    let column = r#"        (name: "mark", plugin: "clear", params: (stencil: Param(name: "mark", default: 7), "#
        .len()
        + 1;
    assert!(
        line.starts_with(&format!("tests/fixtures/inline.ron:9:{column}: error:")),
        "{line}"
    );
}
