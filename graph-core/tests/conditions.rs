//! Conditions in code: passes and resources that exist only for some features, dropped
//! by the first compile phase with the reason, and read through where they modified.

use crate::common;

use common::{tex, CLEAR};
use rgraph_core::types::TextureFormat::{Rgba16Float, Rgba8Unorm};
use rgraph_core::{
    explain, ColorLoad, CompileOptions, Condition, Features, Graph, GraphBuilder, GraphError, Plan,
};

fn compile(graph: &Graph, features: &[&str]) -> Plan {
    graph
        .compile_for(
            &CompileOptions::default(),
            &Features::from_iter(features.iter().copied()),
        )
        .unwrap_or_else(|e| panic!("expected the graph to compile, got:\n{e}"))
}

fn errors(graph: &Graph, features: &[&str]) -> Vec<GraphError> {
    match graph.compile_for(
        &CompileOptions::default(),
        &Features::from_iter(features.iter().copied()),
    ) {
        Ok(_) => panic!("expected the graph to be rejected"),
        Err(e) => e.0,
    }
}

fn live(plan: &Plan) -> Vec<&str> {
    plan.passes.iter().map(|p| p.name.as_str()).collect()
}

fn when(text: &str) -> Condition {
    Condition::parse(text).expect("the condition parses")
}

/// `base` clears "hdr"; `spot` (when spot_lights) and `glow` (when !unlit_only) add to
/// it; `tonemap` reads the result into the exported "color".
fn lighting() -> Graph {
    let mut g = GraphBuilder::new();
    g.declare_features(["spot_lights", "unlit_only"]);
    let hdr = g.create_texture("hdr", tex(Rgba16Float));
    let color = g.create_texture("color", tex(Rgba8Unorm));
    let hdr = g.add_render_pass("base").color_output(hdr, CLEAR);
    let mut spot = g.add_render_pass("spot");
    spot.when(when("spot_lights"));
    let hdr = spot.color_output(hdr, ColorLoad::Load);
    let mut glow = g.add_render_pass("glow");
    glow.when(when("!unlit_only"));
    let hdr = glow.color_output(hdr, ColorLoad::Load);
    let mut tonemap = g.add_render_pass("tonemap");
    tonemap.sampled(hdr);
    let color = tonemap.color_output(color, CLEAR);
    g.export(color);
    g.build()
}

#[test]
fn a_pass_whose_condition_is_false_is_dropped_and_says_why() {
    let plan = compile(&lighting(), &[]);
    assert_eq!(live(&plan), ["base", "glow", "tonemap"]);
    let spot = &plan.culled[0];
    assert_eq!(
        (spot.name.as_str(), spot.reason.as_str(), spot.dropped),
        ("spot", r#"condition "spot_lights" is false"#, true)
    );

    let text = explain::text(&plan);
    assert!(
        text.contains("dropped passes:\n  - spot: condition \"spot_lights\" is false"),
        "{text}"
    );
    let dot = explain::dot(&plan);
    assert!(
        dot.contains(r#"label="spot\ndropped", tooltip="condition 'spot_lights' is false""#),
        "{dot}"
    );
    let json = explain::json(&plan);
    assert!(
        json.contains(r#""reason": "condition \"spot_lights\" is false""#),
        "{json}"
    );

    let lit = compile(&lighting(), &["spot_lights"]);
    assert_eq!(live(&lit), ["base", "spot", "glow", "tonemap"]);
    assert!(lit.culled.is_empty());
}

#[test]
fn readers_of_a_dropped_modification_read_what_it_modified() {
    let graph = lighting();
    let plan = compile(&graph, &["unlit_only"]);
    assert_eq!(live(&plan), ["base", "tonemap"]);
    let hdr = graph.resource_id("hdr").unwrap();
    // Declared, tonemap reads version 3 (base 1, spot 2, glow 3); here base's version 1.
    assert_eq!(plan.pass("tonemap").unwrap().reads, [(hdr, 1)]);
    let glow = plan.culled.iter().find(|c| c.name == "glow").unwrap();
    assert_eq!(glow.reason, r#"condition "!unlit_only" is false"#);
    assert_eq!(glow.reads, [(hdr, 2)]);
    // base's output is now read by tonemap, so it is stored; it was already.
    assert_eq!(plan.pass("base").unwrap().writes, [(hdr, 1)]);
    assert_eq!(plan.features, ["unlit_only"]);
}

#[test]
fn features_the_graph_does_not_declare_are_ignored() {
    let graph = lighting();
    let plain = compile(&graph, &["spot_lights"]);
    let extra = compile(&graph, &["spot_lights", "textures", "fog"]);
    assert_eq!(extra.features, ["spot_lights"]);
    assert_eq!(explain::json(&plain), explain::json(&extra));
}

#[test]
fn a_dropped_pass_that_wrote_fresh_contents_someone_reads_is_named_with_the_reader() {
    let mut g = GraphBuilder::new();
    g.declare_features(["shadows"]);
    let shadow = g.create_texture("shadow", tex(Rgba16Float));
    let color = g.create_texture("color", tex(Rgba8Unorm));
    let mut render = g.add_render_pass("shadow map");
    render.when(Condition::feature("shadows"));
    let shadow = render.color_output(shadow, CLEAR);
    let mut light = g.add_render_pass("light");
    light.sampled(shadow);
    let color = light.color_output(color, CLEAR);
    g.export(color);
    let graph = g.build();

    let errors = errors(&graph, &[]);
    assert_eq!(
        errors,
        [GraphError::DroppedWriter {
            reader: "light".into(),
            dropped: "shadow map".into(),
            resource: "shadow".into(),
            why: r#"condition "shadows" is false"#.into(),
        }]
    );
    assert_eq!(
        errors[0].to_string(),
        r#"pass "light" reads "shadow" as pass "shadow map" writes it, but "shadow map" is dropped (condition "shadows" is false); give "light" a condition that implies "shadow map"'s, or write "shadow" in a pass that stays"#
    );
    assert_eq!(
        live(&compile(&graph, &["shadows"])),
        ["shadow map", "light"]
    );
}

#[test]
fn an_output_only_a_dropped_pass_writes_is_an_error() {
    let mut g = GraphBuilder::new();
    g.declare_features(["debug"]);
    let view = g.create_texture("debug view", tex(Rgba8Unorm));
    let mut pass = g.add_render_pass("debug");
    pass.when(Condition::feature("debug"));
    let view = pass.color_output(view, CLEAR);
    g.export(view);
    let errors = errors(&g.build(), &[]);
    assert_eq!(
        errors[0].to_string(),
        r#"output "debug view" is written by pass "debug", which is dropped (condition "debug" is false); give "debug view" the same condition"#
    );
    assert_eq!(errors.len(), 1);
}

#[test]
fn a_dropped_resource_is_not_allocated_and_says_why() {
    let mut g = GraphBuilder::new();
    g.declare_features(["debug"]);
    let color = g.create_texture("color", tex(Rgba8Unorm));
    let view = g.create_texture("debug view", tex(Rgba16Float));
    g.when(view, Condition::feature("debug"));
    let color = g.add_render_pass("main").color_output(color, CLEAR);
    g.export(color);
    let mut debug = g.add_render_pass("debug");
    debug.when(Condition::feature("debug"));
    debug.sampled(color);
    let view = debug.color_output(view, CLEAR);
    g.export(view);
    let graph = g.build();

    let plain = compile(&graph, &[]);
    let view = plain.find("debug view").unwrap();
    assert_eq!(
        (view.culled.as_deref(), view.physical, view.exported),
        (Some(r#"condition "debug" is false"#), None, false)
    );
    let with_debug = compile(&graph, &["debug"]);
    assert_eq!(live(&with_debug), ["main", "debug"]);
    // 64x64 rgba16float: 32 KiB more.
    assert_eq!(
        with_debug.memory.physical_bytes - plain.memory.physical_bytes,
        64 * 64 * 8
    );
}

#[test]
fn a_live_pass_using_a_dropped_resource_is_an_error() {
    let mut g = GraphBuilder::new();
    g.declare_features(["lit"]);
    let normal = g.create_texture("normal", tex(Rgba16Float));
    g.when(normal, Condition::feature("lit"));
    let normal = g.add_render_pass("gbuffer").color_output(normal, CLEAR);
    g.export(normal);
    let errors = errors(&g.build(), &[]);
    assert_eq!(
        errors[0].to_string(),
        r#"pass "gbuffer" uses "normal", which is dropped (condition "lit" is false); give "gbuffer" a condition that implies the resource's"#
    );
    assert_eq!(errors.len(), 1);
}

/// Two G-buffer passes writing over the same version of "albedo", one per feature set:
/// the reader follows whichever is live.
fn alternatives(second: &str) -> Graph {
    let mut g = GraphBuilder::new();
    g.declare_features(["unlit_only", "lit"]);
    let albedo = g.create_texture("albedo", tex(Rgba8Unorm));
    let color = g.create_texture("color", tex(Rgba8Unorm));
    let mut full = g.add_render_pass("gbuffer");
    full.when(when("!unlit_only"));
    full.color_output(albedo, CLEAR);
    let mut unlit = g.add_render_pass("gbuffer unlit");
    unlit.when(when(second));
    let albedo = unlit.color_output(albedo, CLEAR);
    let mut resolve = g.add_render_pass("resolve");
    resolve.sampled(albedo);
    let color = resolve.color_output(color, CLEAR);
    g.export(color);
    g.build()
}

#[test]
fn passes_with_exclusive_conditions_may_write_one_version_and_the_live_one_is_read() {
    let graph = alternatives("unlit_only");
    let albedo = graph.resource_id("albedo").unwrap();
    let lit = compile(&graph, &[]);
    assert_eq!(live(&lit), ["gbuffer", "resolve"]);
    assert_eq!(lit.pass("resolve").unwrap().reads, [(albedo, 1)]);
    let unlit = compile(&graph, &["unlit_only"]);
    assert_eq!(live(&unlit), ["gbuffer unlit", "resolve"]);
    assert_eq!(unlit.pass("resolve").unwrap().reads, [(albedo, 2)]);
    assert_eq!(
        unlit.culled[0].reason,
        r#"condition "!unlit_only" is false"#
    );
}

#[test]
fn writers_of_one_version_whose_conditions_may_both_hold_conflict_for_every_feature_set() {
    let graph = alternatives("lit");
    for features in [&[][..], &["lit"], &["unlit_only"]] {
        assert_eq!(
            errors(&graph, features),
            [GraphError::ConflictingWriters {
                first: "gbuffer".into(),
                second: "gbuffer unlit".into(),
                resource: "albedo".into(),
                version: 0,
            }]
        );
    }
}

#[test]
fn a_condition_naming_an_undeclared_feature_is_an_error_naming_the_pass_or_resource() {
    let mut g = GraphBuilder::new();
    g.declare_features(["spot_lights", "unlit_only"]);
    let color = g.create_texture("color", tex(Rgba8Unorm));
    g.when(color, when("!unlitonly"));
    let mut pass = g.add_render_pass("spot");
    pass.when(when("spot_light & !unlit_only"));
    let color = pass.color_output(color, CLEAR);
    g.export(color);
    let errors = errors(&g.build(), &["spot_light"]);
    let messages: Vec<String> = errors.iter().map(ToString::to_string).collect();
    assert_eq!(
        messages,
        [
            r#"pass "spot": condition "spot_light & !unlit_only" names feature "spot_light", which the graph does not declare (declared: spot_lights, unlit_only)"#,
            r#"resource "color": condition "!unlitonly" names feature "unlitonly", which the graph does not declare (declared: spot_lights, unlit_only)"#,
        ]
    );
    assert_eq!(errors[0].pass(), Some("spot"));
    assert_eq!(errors[1].resource(), Some("color"));
}

#[test]
fn every_pass_is_in_some_witness_feature_set() {
    let graph = alternatives("unlit_only");
    let witnesses = graph.witnesses();
    assert_eq!(
        witnesses,
        [Features::new(), Features::from_iter(["unlit_only"])]
    );
    let mut seen: Vec<String> = Vec::new();
    for features in &witnesses {
        let plan = compile(&graph, &features.iter().collect::<Vec<_>>());
        seen.extend(plan.passes.iter().map(|p| p.name.clone()));
    }
    seen.sort();
    seen.dedup();
    assert_eq!(seen, ["gbuffer", "gbuffer unlit", "resolve"]);
}

#[test]
fn a_pass_its_plugin_omits_is_dropped_for_every_feature_set_with_the_reason() {
    let mut g = GraphBuilder::new();
    let hdr = g.create_texture("hdr", tex(Rgba16Float));
    let color = g.create_texture("color", tex(Rgba8Unorm));
    let hdr = g.add_render_pass("base").color_output(hdr, CLEAR);
    let mut edges = g.add_render_pass("edges");
    edges.omit("one sample per pixel");
    let hdr = edges.color_output(hdr, ColorLoad::Load);
    let mut tonemap = g.add_render_pass("tonemap");
    tonemap.sampled(hdr);
    let color = tonemap.color_output(color, CLEAR);
    g.export(color);
    let graph = g.build();
    let plan = compile(&graph, &[]);
    assert_eq!(live(&plan), ["base", "tonemap"]);
    let omitted = &plan.culled[0];
    assert_eq!(
        (
            omitted.name.as_str(),
            omitted.reason.as_str(),
            omitted.dropped
        ),
        ("edges", "one sample per pixel", true)
    );
    // What it modified passes through: tonemap reads base's version.
    let hdr = graph.resource_id("hdr").unwrap();
    assert_eq!(plan.pass("tonemap").unwrap().reads, [(hdr, 1)]);
    assert!(
        explain::text(&plan).contains("dropped passes:\n  - edges: one sample per pixel"),
        "{}",
        explain::text(&plan)
    );
}
