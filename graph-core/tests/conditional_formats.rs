//! Conditional formats (`format_if`) and clear values that follow the format
//! (`AspectAccess::ClearByFormat`): the compile picks a texture's format from the
//! features, the plan and `explain::compare` say why, and a depth clear declared before
//! the format is known gets the value for the format picked.

use crate::ron_support;

use rgraph_core::file::{load_str, Registry};
use rgraph_core::types::{Features as DeviceFeatures, TextureFormat as F};
use rgraph_core::{
    explain, AspectAccess, ByFormat, CompileOptions, Condition, DeviceProfile, Features,
    GraphBuilder, Load, Plan, Size, TextureDesc,
};
use ron_support::{assert_error, only_error};

/// 1 for unorm depth, 0 for float: a stand-in for "far" under a convention that follows
/// the format.
fn far(format: F) -> f32 {
    match format {
        F::Depth32Float | F::Depth32FloatStencil8 => 0.0,
        _ => 1.0,
    }
}

/// A depth prepass over a depth-stencil declared as `depth32float-stencil8` with the
/// `depth24plus-stencil8` fallback, and `depth24plus-stencil8` where `shallow` holds.
fn graph() -> rgraph_core::Graph {
    let mut g = GraphBuilder::new();
    g.declare_features(["shallow"]);
    let depth = g.create_texture(
        "depth",
        TextureDesc::new(F::Depth32FloatStencil8)
            .or(F::Depth24PlusStencil8)
            .format_if(Condition::feature("shallow"), F::Depth24PlusStencil8)
            .size(Size::Absolute(64, 64)),
    );
    let mut p = g.add_render_pass("prepass");
    let depth = p.depth_stencil(
        depth,
        AspectAccess::ClearByFormat(ByFormat(far)),
        AspectAccess::Clear(0),
    );
    g.export(depth);
    g.build()
}

/// A device that can make `depth32float-stencil8`.
fn d32s8_device() -> CompileOptions {
    let mut profile = DeviceProfile::webgpu();
    profile.features |= DeviceFeatures::DEPTH32FLOAT_STENCIL8;
    CompileOptions {
        profile,
        ..CompileOptions::default()
    }
}

fn compile(options: &CompileOptions, features: &[&str]) -> Plan {
    graph()
        .compile_for(options, &Features::from_iter(features.iter().copied()))
        .unwrap_or_else(|e| panic!("{e}"))
}

fn depth_clear(plan: &Plan) -> Load<f32> {
    let ds = plan.passes[0].depth_stencil.as_ref().unwrap();
    ds.depth.unwrap().load
}

#[test]
fn the_features_pick_the_format_and_the_plan_says_why() {
    let general = compile(&d32s8_device(), &[]);
    let shallow = compile(&d32s8_device(), &["shallow"]);
    let shape = |plan: &Plan| plan.find("depth").unwrap().texture.unwrap().format;
    assert_eq!(shape(&general), F::Depth32FloatStencil8);
    assert_eq!(general.find("depth").unwrap().format_because, None);
    assert_eq!(shape(&shallow), F::Depth24PlusStencil8);
    assert_eq!(
        shallow.find("depth").unwrap().format_because.as_deref(),
        Some(
            "depth24plus-stencil8 instead of depth32float-stencil8: condition \"shallow\" \
             holds"
        )
    );
    // 8 bytes per texel (depth and stencil as drivers lay them out) against 4.
    assert_eq!(general.memory.physical_bytes, 64 * 64 * 8);
    assert_eq!(shallow.memory.physical_bytes, 64 * 64 * 4);
    let report = explain::compare(&shallow, &general, "the general scene");
    assert!(
        report.contains(
            "    format of depth: depth24plus-stencil8 instead of depth32float-stencil8: \
             condition \"shallow\" holds\n"
        ),
        "{report}"
    );
    assert!(
        report.contains("memory: 16.0 KiB physical instead of 32.0 KiB"),
        "{report}"
    );
}

#[test]
fn a_clear_by_format_gets_the_value_for_the_format_the_compile_picks() {
    // The feature decides.
    assert_eq!(
        depth_clear(&compile(&d32s8_device(), &[])),
        Load::Clear(0.0)
    );
    assert_eq!(
        depth_clear(&compile(&d32s8_device(), &["shallow"])),
        Load::Clear(1.0)
    );
    // The device decides: without the feature depth32float-stencil8 falls back.
    let webgpu = compile(&CompileOptions::default(), &[]);
    assert_eq!(
        webgpu.find("depth").unwrap().texture.unwrap().format,
        F::Depth24PlusStencil8
    );
    assert_eq!(webgpu.find("depth").unwrap().format_because, None);
    assert_eq!(depth_clear(&webgpu), Load::Clear(1.0));
}

/// A conditional format may be another kind of format (a raster's depth where one
/// feature holds, a compute pass's color where it does not): each plan is checked as it
/// is compiled, so the plan that gives a depth attachment a color format fails, naming
/// it, and the other compiles.
#[test]
fn a_conditional_format_of_another_kind_fails_the_plans_whose_passes_cannot_use_it() {
    let mut g = GraphBuilder::new();
    g.declare_features(["shallow"]);
    let depth = g.create_texture(
        "depth",
        TextureDesc::new(F::Depth24PlusStencil8)
            .format_if(Condition::feature("shallow"), F::Rgba8Unorm),
    );
    let mut p = g.add_render_pass("prepass");
    let depth = p.depth_stencil(depth, AspectAccess::Clear(1.0), AspectAccess::Clear(0));
    g.export(depth);
    let graph = g.build();
    graph
        .compile_for(&CompileOptions::default(), &Features::new())
        .unwrap();
    let errors = graph
        .compile_for(
            &CompileOptions::default(),
            &Features::from_iter(["shallow"]),
        )
        .unwrap_err()
        .0;
    assert!(
        errors.iter().any(|e| e.to_string().contains("rgba8unorm")),
        "{errors:?}"
    );
}

const PATH: &str = "tests/fixtures/inline.ron";

fn file(condition: &str) -> String {
    format!(
        r#"Graph(
features: ["shallow"],
resources: {{
    "depth": Texture(format: "depth32float-stencil8", fallback: "depth24plus-stencil8",
                     format_if: [("{condition}", "depth24plus-stencil8")]),
}},
passes: [
    (name: "clear depth", plugin: "clear", outputs: {{ "target": "depth" }}),
],
outputs: ["depth"],
)"#
    )
}

#[test]
fn a_file_writes_conditional_formats_as_condition_format_pairs() {
    let loaded = load_str(PATH, &file("shallow"), &Registry::with_builtins()).unwrap();
    let features = Features::from_iter(["shallow"]);
    let plan = loaded
        .compile_for(&d32s8_device(), &features)
        .unwrap_or_else(|e| panic!("{e}"));
    let depth = plan.find("depth").unwrap();
    assert_eq!(depth.texture.unwrap().format, F::Depth24PlusStencil8);
    assert!(depth.format_because.is_some());
}

#[test]
fn an_unknown_feature_in_a_conditional_format_is_an_error_where_it_is_written() {
    let text = file("!shalow");
    let error = only_error(
        load_str(PATH, &text, &Registry::with_builtins())
            .and_then(|g| g.compile(&CompileOptions::default())),
    );
    // Line 5, at the "s" after `[("!`.
    let column = text.lines().nth(4).unwrap().find("shalow").unwrap() + 1;
    assert_error(&error, PATH, 5, column, &["depth", "shalow", "!shalow"]);
    assert!(error.to_string().contains("conditional format"), "{error}");
}
