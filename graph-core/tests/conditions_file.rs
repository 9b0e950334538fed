//! Conditions in graph files: `features: [..]` declares the names `when:` may use, a
//! condition naming anything else is an error at the character at fault, and passes with
//! exclusive conditions may write the same name.

use crate::ron_support;

use rgraph_core::file::{load_str, validate_file, ErrorKind, FileErrors, Registry};
use rgraph_core::{CompileOptions, Features, GraphError, Plan, PlanCache};
use ron_support::{assert_error, only_error};

const PATH: &str = "tests/fixtures/inline.ron";

/// A sky drawn into "hdr", rings added to it where `rings` is set, and "hdr" blitted
/// into "color". Where `sky_when` is given, a second sky pass writes "hdr" under it.
fn graph(rings_when: &str, sky_when: &str) -> String {
    format!(
        r#"Graph(
features: ["rings", "night"],
resources: {{
    "hdr": Texture(format: "rgba8unorm", when: "!night | rings"),
    "color": Texture(format: "rgba8unorm"),
}},
passes: [
    (name: "sky", plugin: "clear", when: "{sky_when}", outputs: {{ "target": "hdr" }}),
    (name: "night sky", plugin: "clear", when: "night", outputs: {{ "target": "hdr" }}),
    (name: "rings", plugin: "fullscreen", when: "{rings_when}",
     params: (shader: "../../../shaders/rings.wgsl", blend: Additive),
     inputs: {{ "color": "hdr" }}, outputs: {{ "color": "hdr_rings" }}),
    (name: "present", plugin: "blit", inputs: {{ "src": "hdr_rings" }}, outputs: {{ "dst": "color" }}),
],
outputs: ["color"],
)"#
    )
}

/// The valid variant: no condition on "hdr", sky and night sky exclusive.
fn valid() -> String {
    graph("rings", "!night").replace(r#", when: "!night | rings""#, "")
}

fn load(text: &str) -> Result<rgraph_core::file::LoadedGraph, FileErrors> {
    load_str(PATH, text, &ron_support::registry())
}

fn compile(text: &str, features: &[&str]) -> Plan {
    let features = Features::from_iter(features.iter().copied());
    load(text)
        .and_then(|g| g.compile_for(&CompileOptions::default(), &features))
        .unwrap_or_else(|e| panic!("expected the graph to compile, got:\n{e}"))
}

/// Line and column (1-based, in characters) of the first `needle` in `text`, plus
/// `skip` characters: where an error about it must point.
fn at(text: &str, needle: &str, skip: usize) -> (usize, usize) {
    let offset = text.find(needle).expect("the needle is in the text");
    let before = &text[..offset];
    let line_start = before.rfind('\n').map_or(0, |i| i + 1);
    (
        1 + before.matches('\n').count(),
        1 + before[line_start..].chars().count() + skip,
    )
}

fn live(plan: &Plan) -> Vec<&str> {
    plan.passes.iter().map(|p| p.name.as_str()).collect()
}

#[test]
fn a_file_chooses_passes_by_feature_and_says_why_the_rest_are_dropped() {
    let day = compile(&valid(), &[]);
    assert_eq!(live(&day), ["sky", "present"]);
    let reasons: Vec<(&str, &str)> = day
        .culled
        .iter()
        .map(|c| (c.name.as_str(), c.reason.as_str()))
        .collect();
    assert_eq!(
        reasons,
        [
            ("night sky", r#"condition "night" is false"#),
            ("rings", r#"condition "rings" is false"#),
        ]
    );
    assert_eq!(
        live(&compile(&valid(), &["night", "rings"])),
        ["night sky", "rings", "present"]
    );
}

#[test]
fn an_undeclared_feature_in_a_pass_condition_is_an_error_at_the_feature() {
    let text = valid().replace(r#"when: "rings""#, r#"when: "!night & ring""#);
    let error = only_error(load(&text).map(|_| unreachable!()));
    assert!(matches!(
        error.kind,
        ErrorKind::Graph(GraphError::UnknownPassFeature { .. })
    ));
    let (line, column) = at(&text, "ring\"", 0);
    assert_error(&error, PATH, line, column, &["rings", "ring"]);
    assert!(
        error
            .to_string()
            .ends_with("which the graph does not declare (declared: night, rings)"),
        "{error}"
    );
}

#[test]
fn an_undeclared_feature_in_a_resource_condition_is_an_error_at_the_feature() {
    let text = valid().replace(
        r#""hdr": Texture(format: "rgba8unorm")"#,
        r#""hdr": Texture(format: "rgba8unorm", when: "nigth")"#,
    );
    let error = only_error(load(&text).map(|_| unreachable!()));
    let (line, column) = at(&text, "nigth", 0);
    assert_error(&error, PATH, line, column, &["hdr", "nigth"]);
}

#[test]
fn a_condition_that_does_not_parse_is_an_error_at_the_character_at_fault() {
    let text = graph("rings", "!night");
    let error = only_error(load(&text).map(|_| unreachable!()));
    assert!(matches!(error.kind, ErrorKind::BadCondition { .. }));
    let (line, column) = at(&text, "| rings", 0);
    assert_error(&error, PATH, line, column, &["hdr", "!night | rings"]);
    assert!(
        error.to_string().contains("found '|' after a feature"),
        "{error}"
    );
}

#[test]
fn writers_of_one_name_must_have_exclusive_conditions() {
    let text = graph("rings", "rings").replace(r#", when: "!night | rings""#, "");
    let error = only_error(load(&text).map(|_| unreachable!()));
    assert!(matches!(error.kind, ErrorKind::WritersNotExclusive { .. }));
    // At the second writer's output name.
    let (line, column) = at(
        &text,
        r#""hdr" }),
    (name: "rings""#,
        0,
    );
    assert_error(
        &error,
        PATH,
        line,
        column,
        &["sky", "night sky", "hdr", "rings", "night"],
    );
}

#[test]
fn feature_names_are_checked_where_they_are_declared() {
    let text = valid().replace(
        r#"["rings", "night"]"#,
        r#"["rings", "night", "rings", "2d"]"#,
    );
    let errors = load(&text).map(|_| ()).unwrap_err();
    let messages: Vec<String> = errors.0.iter().map(ToString::to_string).collect();
    assert_eq!(
        messages,
        [
            format!(r#"{PATH}:2:30: error: feature "rings" is declared twice"#),
            format!(
                r#"{PATH}:2:39: error: "2d" is not a feature name: feature names are ASCII letters, digits and '_', not starting with a digit"#
            ),
        ]
    );
}

#[test]
fn validating_a_file_checks_the_passes_every_feature_set_keeps() {
    // The night sky clears a texture that cannot be a color attachment: the plan for
    // no features drops it, but validation compiles for "night" too.
    let text = valid().replace(
        r#""color": Texture(format: "rgba8unorm"),"#,
        r#""color": Texture(format: "rgba8unorm"),
    "stars": Texture(format: "depth32float", when: "night"),"#,
    ).replace(
        r#"(name: "night sky", plugin: "clear", when: "night", outputs: { "target": "hdr" }),"#,
        r#"(name: "night sky", plugin: "clear", when: "night", outputs: { "target": "hdr" }),
    (name: "stars", plugin: "blit", when: "night", inputs: { "src": "hdr" }, outputs: { "dst": "stars" }),"#,
    ).replace(r#"outputs: ["color"]"#, r#"outputs: ["color", "stars"]"#);
    // The file in a folder of its own, with its shader beside it.
    let dir = std::env::temp_dir().join(format!("conditions-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let shader = concat!(env!("CARGO_MANIFEST_DIR"), "/../shaders/rings.wgsl");
    std::fs::copy(shader, dir.join("rings.wgsl")).unwrap();
    let path = dir.join("night.ron");
    std::fs::write(&path, text.replace("../../../shaders/", "")).unwrap();
    assert!(compile(&text, &[]).culled.iter().any(|c| c.name == "stars"));
    let errors = validate_file(
        &path,
        &Registry::with_builtins(),
        &CompileOptions::default(),
    )
    .expect_err("the night graph is invalid");
    assert!(
        errors.to_string().contains(r#"pass "stars""#)
            && errors.to_string().contains("depth32float"),
        "{errors}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn the_plan_cache_compiles_each_feature_set_once() {
    let loaded = load(&valid()).unwrap();
    let options = CompileOptions::default();
    let mut cache = PlanCache::new();
    let scene = |f: &[&str]| Features::from_iter(f.iter().copied());
    let first = live(
        cache
            .get_or_compile(&loaded, &options, &scene(&["rings"]))
            .unwrap(),
    )
    .join(", ");
    // A second scene with the same features, plus one the graph does not declare.
    let second = cache
        .get_or_compile(&loaded, &options, &scene(&["rings", "textures"]))
        .unwrap();
    assert_eq!(live(second).join(", "), first);
    assert_eq!((cache.hits(), cache.misses()), (1, 1));
    cache
        .get_or_compile(&loaded, &options, &scene(&["night"]))
        .unwrap();
    let smaller = CompileOptions {
        output_size: (64, 64),
        ..CompileOptions::default()
    };
    cache
        .get_or_compile(&loaded, &smaller, &scene(&["rings"]))
        .unwrap();
    assert_eq!((cache.hits(), cache.misses(), cache.len()), (1, 3, 3));
}

/// "sky" where the device is not or has not what the device condition `condition` stands
/// for, "fast sky" where it is or has: a device condition, which the profile sets and the
/// caller cannot.
fn device_branches(condition: &str, fast_target: &str) -> String {
    format!(
        r#"Graph(
features: ["{condition}"],
resources: {{
    "hdr": Texture(format: "rgba8unorm"),
    "scratch": Texture(format: "{fast_target}", when: "{condition}"),
}},
passes: [
    (name: "sky", plugin: "clear", when: "!{condition}", outputs: {{ "target": "hdr" }}),
    (name: "fast sky", plugin: "clear", when: "{condition}", outputs: {{ "target": "scratch" }}),
    (name: "present", plugin: "blit", when: "{condition}", inputs: {{ "src": "scratch" }}, outputs: {{ "dst": "hdr" }}),
],
outputs: ["hdr"],
)"#
    )
}

/// Each device condition, and a profile of a device that sets it.
fn device_conditions() -> [(&'static str, rgraph_core::DeviceProfile); 3] {
    let mut atomics = rgraph_core::DeviceProfile::webgpu();
    atomics.features = rgraph_core::types::Features::SHADER_INT64
        | rgraph_core::types::Features::SHADER_INT64_ATOMIC_MIN_MAX;
    let mut cpu = rgraph_core::DeviceProfile::webgpu();
    cpu.cpu = true;
    let mut wide = rgraph_core::DeviceProfile::webgpu();
    wide.limits.max_color_attachment_bytes_per_sample = 128;
    [
        ("int64_atomics", atomics),
        ("cpu_device", cpu),
        ("color_bytes_64", wide),
    ]
}

#[test]
fn device_conditions_come_from_the_profile_not_the_caller() {
    for (condition, profile) in device_conditions() {
        let text = device_branches(condition, "rgba8unorm");
        let loaded = load(&text).unwrap();
        let asked = Features::from_iter([condition]);
        let webgpu = loaded
            .compile_for(&CompileOptions::default(), &asked)
            .unwrap();
        assert_eq!(live(&webgpu), ["sky"], "{condition}");
        assert!(webgpu.features.is_empty(), "{:?}", webgpu.features);
        let options = CompileOptions {
            profile,
            ..CompileOptions::default()
        };
        let device = loaded.compile_for(&options, &Features::new()).unwrap();
        assert_eq!(live(&device), ["fast sky", "present"], "{condition}");
        assert_eq!(device.features, [condition]);
    }
}

/// A plan compiled from the caller's features, and asked for again with its own (which
/// hold the device's conditions, as a resize does), is the same cached plan.
#[test]
fn a_plan_s_own_features_find_it_in_the_cache() {
    for (condition, profile) in device_conditions() {
        let loaded = load(&device_branches(condition, "rgba8unorm")).unwrap();
        let options = CompileOptions {
            profile,
            ..CompileOptions::default()
        };
        let mut cache = PlanCache::new();
        let features = Features::from_iter(
            (cache.get_or_compile(&loaded, &options, &Features::new()))
                .unwrap()
                .features
                .iter()
                .map(String::as_str),
        );
        assert!(features.contains(condition), "{condition}");
        cache.get_or_compile(&loaded, &options, &features).unwrap();
        assert_eq!((cache.hits(), cache.misses()), (1, 1), "{condition}");
    }
}

#[test]
fn validation_checks_a_device_branch_on_a_profile_without_the_device_condition() {
    let dir = std::env::temp_dir().join(format!("device-conditions-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (condition, _) in device_conditions() {
        let path = dir.join(format!("{condition}.ron"));
        // The fast branch blits into a compressed texture: wrong on every device.
        std::fs::write(&path, device_branches(condition, "bc1-rgba-unorm")).unwrap();
        let errors = validate_file(
            &path,
            &Registry::with_builtins(),
            &CompileOptions::default(),
        )
        .expect_err("the fast branch is invalid");
        assert!(
            errors.to_string().contains(r#""scratch""#)
                && errors.to_string().contains("bc1-rgba-unorm"),
            "{condition}: {errors}"
        );
        std::fs::write(&path, device_branches(condition, "rgba8unorm")).unwrap();
        validate_file(
            &path,
            &Registry::with_builtins(),
            &CompileOptions::default(),
        )
        .unwrap();
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
