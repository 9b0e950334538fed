//! Optional reads: a pass that can do without an input (a light pass without shadow
//! maps) marks its read optional, in code (`PassBuilder::optional`) or in a file
//! (`optional: ["slot"]`). Where a condition drops the resource or the pass that alone
//! writes it, the compile drops the read, the plan and `explain` say why, and on a
//! device the pass runs and finds the input missing (`FrameResources::has`); where the
//! writer stays, the read is an ordinary one. A fresh write can be optional too (a
//! G-buffer target only some scenes keep): where a condition drops the resource, the
//! compile drops the write. A modification cannot be optional.

use std::cell::RefCell;
use std::rc::Rc;

use crate::common::{tex, CLEAR};
use crate::ron_support::{assert_error, compile_str, only_error};
use rgraph_core::file::{load_str, ErrorKind, LoadedGraph, Registry};
use rgraph_core::gpu::{AdapterChoice, Executor, Gpu, Imports};
use rgraph_core::types::TextureFormat::{Depth32Float, Rgba8Unorm};
use rgraph_core::{
    explain, Aspect, AspectAccess, ColorLoad, CompileOptions, CompiledGraph, Condition,
    DroppedRead, Features, Graph, GraphBuilder, GraphError, Plan, PlannedPass, ResourceId,
};

fn compile(graph: &Graph, features: &[&str]) -> Plan {
    graph
        .compile_for(
            &CompileOptions::default(),
            &Features::from_iter(features.iter().copied()),
        )
        .unwrap_or_else(|e| panic!("expected the graph to compile, got:\n{e}"))
}

fn pass<'p>(plan: &'p Plan, name: &str) -> &'p PlannedPass {
    plan.passes
        .iter()
        .find(|p| p.name == name)
        .unwrap_or_else(|| panic!("no live pass {name}"))
}

/// "shadow maps" (when `shadows`) writes "atlas", which "light" samples, optionally
/// where `optional`; "light" writes the exported "color". With `atlas_when` the atlas
/// itself has the condition too, as the shipped pipelines write it.
fn lights(optional: bool, atlas_when: bool) -> Graph {
    let mut g = GraphBuilder::new();
    g.declare_features(["shadows"]);
    let atlas = g.create_texture("atlas", tex(Depth32Float));
    if atlas_when {
        g.when(atlas, Condition::feature("shadows"));
    }
    let color = g.create_texture("color", tex(Rgba8Unorm));
    let mut maps = g.add_render_pass("shadow maps");
    maps.when(Condition::feature("shadows"));
    let atlas = maps.depth_stencil(atlas, AspectAccess::Clear(1.0), AspectAccess::ReadOnly);
    let mut light = g.add_render_pass("light");
    light.sampled_aspect(atlas, Aspect::DepthOnly);
    if optional {
        light.optional(atlas);
    }
    let color = light.color_output(color, CLEAR);
    g.export(color);
    g.build()
}

#[test]
fn where_the_writer_stays_an_optional_read_is_an_ordinary_one() {
    let plan = compile(&lights(true, false), &["shadows"]);
    let light = pass(&plan, "light");
    assert_eq!(light.reads, [(ResourceId(0), 1)]);
    assert!(light.dropped_reads.is_empty());
    assert_eq!(
        explain::text(&plan),
        explain::text(&compile(&lights(false, false), &["shadows"])),
        "marking the read optional changes nothing while it stays"
    );
}

#[test]
fn where_its_writer_is_dropped_the_read_is_dropped_and_the_plan_says_why() {
    let plan = compile(&lights(true, false), &[]);
    let names: Vec<&str> = plan.passes.iter().map(|p| p.name.as_str()).collect();
    assert_eq!(names, ["light"]);
    let light = pass(&plan, "light");
    assert!(light.reads.is_empty(), "{:?}", light.reads);
    let why = r#"its writer "shadow maps" is dropped: condition "shadows" is false"#;
    assert_eq!(
        light.dropped_reads,
        [DroppedRead {
            resource: ResourceId(0),
            version: 1,
            why: why.to_owned(),
            writes: false,
        }]
    );
    // Nothing reads the atlas, so nothing allocates it.
    assert!(plan.resources[0].physical.is_none());
    let text = explain::text(&plan);
    assert!(
        text.contains(&format!(
            "         writes  color@1\n         skips   atlas@1 (an \
             optional read): {why}\n"
        )),
        "{text}"
    );
    let json = explain::json(&plan);
    assert!(json.contains(r#""dropped_reads""#), "{json}");
}

#[test]
fn where_the_resource_is_dropped_the_read_is_dropped_with_the_resource_s_condition() {
    let plan = compile(&lights(true, true), &[]);
    let light = pass(&plan, "light");
    assert_eq!(
        light.dropped_reads[0].why,
        r#""atlas" is dropped: condition "shadows" is false"#
    );
    assert_eq!(
        plan.resources[0].culled.as_deref(),
        Some(r#"condition "shadows" is false"#)
    );
    assert!(pass(&compile(&lights(true, true), &["shadows"]), "light")
        .dropped_reads
        .is_empty());
}

#[test]
fn a_read_that_is_not_optional_still_fails_naming_the_dropped_writer() {
    let graph = lights(false, false);
    let errors = graph
        .compile_for(&CompileOptions::default(), &Features::new())
        .expect_err("the light pass reads what nothing writes");
    assert_eq!(
        errors.0,
        [GraphError::DroppedWriter {
            reader: "light".into(),
            dropped: "shadow maps".into(),
            resource: "atlas".into(),
            why: r#"condition "shadows" is false"#.into(),
        }]
    );
    let errors = lights(false, true)
        .compile_for(&CompileOptions::default(), &Features::new())
        .expect_err("the light pass reads a dropped resource");
    assert!(
        matches!(&errors.0[..], [GraphError::UsesDroppedResource { pass, .. }] if pass == "light"),
        "{errors}"
    );
}

#[test]
fn an_optional_read_of_a_dropped_modification_reads_through_it() {
    // "glow" adds to "hdr" where `glow` is set: without it, "present" reads what "base"
    // wrote, and keeps its read.
    let mut g = GraphBuilder::new();
    g.declare_features(["glow"]);
    let hdr = g.create_texture("hdr", tex(Rgba8Unorm));
    let color = g.create_texture("color", tex(Rgba8Unorm));
    let hdr = g.add_render_pass("base").color_output(hdr, CLEAR);
    let mut glow = g.add_render_pass("glow");
    glow.when(Condition::feature("glow"));
    let hdr = glow.color_output(hdr, ColorLoad::Load);
    let mut present = g.add_render_pass("present");
    present.sampled(hdr);
    present.optional(hdr);
    let color = present.color_output(color, CLEAR);
    g.export(color);
    let plan = compile(&g.build(), &[]);
    let present = pass(&plan, "present");
    assert_eq!(present.reads, [(ResourceId(0), 1)]);
    assert!(present.dropped_reads.is_empty());
}

#[test]
fn only_a_read_or_a_fresh_write_the_pass_declared_can_be_optional() {
    let mut g = GraphBuilder::new();
    let color = g.create_texture("color", tex(Rgba8Unorm));
    let other = g.create_texture("other", tex(Rgba8Unorm));
    let mut pass = g.add_render_pass("draw");
    pass.optional(color);
    let written = pass.color_output(color, CLEAR);
    pass.optional(color);
    pass.optional(other);
    let mut blend = g.add_render_pass("blend");
    let blended = blend.color_output(written, ColorLoad::Load);
    blend.optional(written);
    g.export(blended);
    let errors = g
        .build()
        .compile(&CompileOptions::default())
        .expect_err("optional modifications are refused");
    let messages: Vec<String> = errors.0.iter().map(ToString::to_string).collect();
    assert_eq!(
        messages,
        [
            r#"pass "draw" marks "color" optional, but the pass declared no access to it"#,
            r#"pass "draw" marks "other" optional, but the pass declared no access to it"#,
            r#"pass "blend" marks "color" optional, but the pass modifies it: only a read or a fresh write can be optional"#,
        ]
    );
}

/// "gbuffer" writes "albedo" and, optionally, "layers" (which exists where `layers` is
/// set); "light" reads both, "layers" optionally, and writes the exported "color".
fn optional_target() -> Graph {
    let mut g = GraphBuilder::new();
    g.declare_features(["layers"]);
    let albedo = g.create_texture("albedo", tex(Rgba8Unorm));
    let layers = g.create_texture("layers", tex(Rgba8Unorm));
    g.when(layers, Condition::feature("layers"));
    let color = g.create_texture("color", tex(Rgba8Unorm));
    let mut gbuffer = g.add_render_pass("gbuffer");
    let albedo = gbuffer.color_output(albedo, CLEAR);
    let written = gbuffer.color_output(layers, CLEAR);
    gbuffer.optional(layers);
    let mut light = g.add_render_pass("light");
    light.sampled(albedo);
    light.sampled(written);
    light.optional(written);
    let color = light.color_output(color, CLEAR);
    g.export(color);
    g.build()
}

#[test]
fn an_optional_write_is_dropped_with_its_resource_and_kept_with_it() {
    let with = compile(&optional_target(), &["layers"]);
    let gbuffer = pass(&with, "gbuffer");
    assert_eq!(gbuffer.color.len(), 2);
    assert!(gbuffer.dropped_reads.is_empty());
    assert_eq!(pass(&with, "light").reads.len(), 2);
    let without = compile(&optional_target(), &[]);
    let gbuffer = pass(&without, "gbuffer");
    assert_eq!(gbuffer.color.len(), 1, "the dropped target is not attached");
    let why = r#""layers" is dropped: condition "layers" is false"#;
    assert_eq!(
        gbuffer.dropped_reads,
        [DroppedRead {
            resource: ResourceId(1),
            version: 0,
            why: why.to_owned(),
            writes: true,
        }]
    );
    assert_eq!(pass(&without, "light").reads, [(ResourceId(0), 1)]);
    let text = explain::text(&without);
    assert!(
        text.contains(&format!("skips   layers@0 (an optional write): {why}\n")),
        "{text}"
    );
}

/// A sky cleared into "hdr" where `sky` is set, blitted into "color" by "present", whose
/// `src` read is optional (as `optional` writes it).
fn file(optional: &str) -> String {
    format!(
        r#"Graph(
features: ["sky"],
resources: {{
    "hdr": Texture(format: "rgba8unorm", when: "sky"),
    "color": Texture(format: "rgba8unorm"),
}},
passes: [
    (name: "sky", plugin: "clear", when: "sky", outputs: {{ "target": "hdr" }}),
    (name: "present", plugin: "blit", inputs: {{ "src": "hdr" }}, outputs: {{ "dst": "color" }},
     optional: [{optional}]),
],
outputs: ["color"],
)"#
    )
}

const PATH: &str = "tests/fixtures/inline.ron";

fn load(text: &str) -> Result<LoadedGraph, rgraph_core::file::FileErrors> {
    load_str(PATH, text, &Registry::with_builtins())
}

#[test]
fn a_file_marks_a_slot_optional() {
    let loaded = load(&file(r#""src""#)).unwrap_or_else(|e| panic!("{e}"));
    let options = CompileOptions::default();
    let with = loaded
        .compile_for(&options, &Features::from_iter(["sky"]))
        .unwrap();
    assert_eq!(pass(&with, "present").reads.len(), 1);
    let without = loaded.compile_for(&options, &Features::new()).unwrap();
    let present = pass(&without, "present");
    assert!(present.reads.is_empty());
    assert_eq!(
        present.dropped_reads[0].why,
        r#""hdr" is dropped: condition "sky" is false"#
    );
    // Without `optional` the same file is refused where the sky is dropped.
    assert!(compile_str(&file("")).is_err());
}

#[test]
fn a_file_s_optional_slot_must_be_an_input_only_or_an_output_only_slot() {
    // "present" blits over a cleared "base", so its `dst` modifies it.
    let modified = file(r#""dst""#)
        .replace(r#""color": Texture"#, r#""base": Texture"#)
        .replace(
            r#"inputs: { "src": "hdr" }"#,
            r#"inputs: { "src": "hdr", "dst": "base" }"#,
        )
        .replace(
            "    (name: \"present\"",
            "    (name: \"base\", plugin: \"clear\", outputs: { \"target\": \"base\" }),\n    (name: \"present\"",
        );
    for (text, slot, why) in [
        (
            modified,
            "dst",
            "is in its inputs and outputs: a modification cannot be optional",
        ),
        (
            file(r#""sky""#),
            "sky",
            "is not one of its inputs or outputs",
        ),
    ] {
        let error = only_error(compile_str(&text));
        assert!(
            matches!(&error.kind, ErrorKind::OptionalSlot { why: w, .. } if w == why),
            "{error}"
        );
        let at = text.rfind(&format!("[\"{slot}\"")).unwrap() + 1;
        let line = text[..at].lines().count();
        let column = at - text[..at].rfind('\n').unwrap();
        assert_error(&error, PATH, line, column, &["present", slot]);
    }
    // An output-only slot may be optional.
    let loaded = load(&file(r#""src", "dst""#)).unwrap_or_else(|e| panic!("{e}"));
    assert!(loaded.slot("present", "dst").is_some());
    assert!(loaded.slot("present", "nothing").is_none());
}

#[test]
fn a_use_of_a_part_has_no_optional() {
    let text = file(r#""src""#).replace("outputs: [\"color\"],", "outputs: [\"color\"],\n");
    let text = text.replace(
        "    (name: \"sky\",",
        "    (part: \"nowhere.ron\", optional: [\"x\"]),\n    (name: \"sky\",",
    );
    let errors = load(&text).map(|_| ()).unwrap_err();
    assert!(
        errors.to_string().contains(
            "a use of a part has no `optional`: which reads are optional is written at the \
             part's passes"
        ),
        "{errors}"
    );
}

#[test]
fn on_a_device_the_pass_finds_its_optional_input_missing_where_the_plan_drops_it() {
    let gpu = Gpu::open(&AdapterChoice::from_env())
        .unwrap_or_else(|e| panic!("this test needs a Vulkan adapter: {e}"));
    let mut g = GraphBuilder::new();
    g.declare_features(["shadows"]);
    let atlas = g.create_texture("atlas", tex(Depth32Float));
    let color = g.create_texture("color", tex(Rgba8Unorm));
    let mut maps = g.add_render_pass("shadow maps");
    maps.when(Condition::feature("shadows"));
    let atlas = maps.depth_stencil(atlas, AspectAccess::Clear(1.0), AspectAccess::ReadOnly);
    maps.render(|_| {});
    let mut light = g.add_render_pass("light");
    light.sampled_aspect(atlas, Aspect::DepthOnly);
    light.optional(atlas);
    let color = light.color_output(color, CLEAR);
    let seen = Rc::new(RefCell::new(Vec::new()));
    let record = seen.clone();
    light.render(move |ctx| {
        let has = ctx.resources.has(atlas);
        if has {
            // Present: its view can be looked up.
            let _ = ctx.resources.aspect_view(atlas, Aspect::DepthOnly);
        }
        record.borrow_mut().push(has);
    });
    g.export(color);
    let options = CompileOptions {
        output_size: (8, 8),
        profile: gpu.profile(),
    };
    let shadows = Features::from_iter(["shadows"]);
    let mut compiled =
        CompiledGraph::new_for(g.build(), &options, &shadows).unwrap_or_else(|e| panic!("{e}"));
    let mut executor = Executor::new(&gpu);
    executor
        .execute(&mut compiled, &Imports::new())
        .unwrap_or_else(|e| panic!("{e}"));
    compiled.recompile(&options, &Features::new()).unwrap();
    executor
        .execute(&mut compiled, &Imports::new())
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(*seen.borrow(), [true, false]);
}
