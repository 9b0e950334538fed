//! A graph file and its code-built twin compile to the same plan: loading goes through
//! the same builder and compile as code does.

use crate::ron_support;

use rgraph_core::file::load_file;
use rgraph_core::types::TextureFormat;
use rgraph_core::{ColorLoad, CompileOptions, Graph, GraphBuilder, Plan, TextureDesc, Workgroup};

fn plan_json(plan: &Plan) -> serde_json::Value {
    serde_json::to_value(plan).expect("plans serialize")
}

/// `pipelines/postprocess_demo.ron`, declared in code the way its plugins declare it.
fn postprocess_twin() -> Graph {
    let mut g = GraphBuilder::new();
    let hdr = g.create_texture("hdr", TextureDesc::new(TextureFormat::Rgba16Float));
    let toned = g.create_texture("toned", TextureDesc::new(TextureFormat::Rgba16Float));
    let target = g.import_texture("target", TextureDesc::new(TextureFormat::Rgba8UnormSrgb));
    let clear = ColorLoad::Clear([0.0; 4]);

    let hdr = g.add_render_pass("sky").color_output(hdr, clear);
    let mut tonemap = g.add_compute_pass("tonemap");
    // shaders/exposure.wgsl's entry point: 8x8 invocations, no workgroup memory.
    tonemap.workgroup(Workgroup {
        entry: "main".into(),
        size: [8, 8, 1],
        memory_bytes: 0,
    });
    tonemap.sampled(hdr);
    let toned = tonemap.storage_write(toned);
    let mut present = g.add_render_pass("present");
    present.sampled(toned);
    let target = present.color_output(target, clear);
    g.export(target);
    g.build()
}

/// `pipelines/msaa_demo.ron`: a clear, a pass modifying its output, a sampled 4x input.
fn msaa_twin() -> Graph {
    let mut g = GraphBuilder::new();
    let msaa = g.create_texture(
        "msaa",
        TextureDesc::new(TextureFormat::Rgba8Unorm).samples(4),
    );
    let resolved = g.create_texture("resolved", TextureDesc::new(TextureFormat::Rgba8Unorm));

    let msaa = g
        .add_render_pass("clear")
        .color_output(msaa, ColorLoad::Clear([0.05, 0.05, 0.1, 1.0]));
    let msaa_rings = g
        .add_render_pass("rings")
        .color_output(msaa, ColorLoad::Load);
    let mut average = g.add_render_pass("average");
    average.sampled(msaa_rings);
    let resolved = average.color_output(resolved, ColorLoad::Clear([0.0; 4]));
    g.export(resolved);
    g.build()
}

fn assert_same_plan(file: &str, twin: Graph) {
    let options = CompileOptions::default();
    let loaded = load_file(file, &ron_support::registry()).unwrap_or_else(|e| panic!("{e}"));
    let from_file = loaded.compile(&options).unwrap_or_else(|e| panic!("{e}"));
    let from_code = twin.compile(&options).expect("the twin compiles");
    assert_eq!(plan_json(&from_file), plan_json(&from_code));
}

#[test]
fn postprocess_demo_compiles_to_the_plan_of_its_code_twin() {
    assert_same_plan("../pipelines/postprocess_demo.ron", postprocess_twin());
}

#[test]
fn msaa_demo_compiles_to_the_plan_of_its_code_twin() {
    assert_same_plan("../pipelines/msaa_demo.ron", msaa_twin());
}
