//! Graph-file parameters: `samples: Param(name: "msaa", default: 4)` takes its default, or
//! the value the loader is given; a value for an undeclared parameter, a value of 0 and
//! two defaults for one name are errors at their place in the file.

use graph_core::file::{
    declared_params, load_str, load_str_with, ErrorKind, GraphParams, Registry,
};
use graph_core::CompileOptions;

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
            graph_core::ResourceDesc::Texture(t) => Some((r.name.clone(), t.samples)),
            graph_core::ResourceDesc::Buffer(_) => None,
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
    let declared = declared_params(&path);
    std::fs::remove_file(&path).unwrap();
    assert_eq!(declared.unwrap(), GraphParams::new().with("msaa", 4));
}
