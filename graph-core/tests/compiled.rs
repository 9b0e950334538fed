//! A graph bound to its plans: recompiling for another output size caches each plan, a
//! failed recompile keeps the plan that was current, and the graph comes back unbound.

use rgraph_core::types::TextureFormat::Rgba8Unorm;
use rgraph_core::{ColorLoad, CompileOptions, CompiledGraph, Features, GraphBuilder, TextureDesc};

/// One output-sized target, cleared and exported.
fn graph() -> rgraph_core::Graph {
    let mut g = GraphBuilder::new();
    let target = g.create_texture("target", TextureDesc::new(Rgba8Unorm));
    let out = g
        .add_render_pass("clear")
        .color_output(target, ColorLoad::Clear([0.0; 4]));
    g.export(out);
    g.build()
}

fn at(size: (u32, u32)) -> CompileOptions {
    CompileOptions {
        output_size: size,
        ..CompileOptions::default()
    }
}

#[test]
fn recompiling_switches_the_plan_and_caches_each() {
    let mut compiled = CompiledGraph::new(graph(), &at((64, 32))).unwrap();
    assert_eq!(compiled.plan().output_size, (64, 32));
    let none = Features::new();
    compiled.recompile(&at((16, 16)), &none).unwrap();
    assert_eq!(compiled.plan().output_size, (16, 16));
    compiled.recompile(&at((64, 32)), &none).unwrap();
    assert_eq!(compiled.plan().output_size, (64, 32));
    let plans = compiled.plans();
    assert_eq!((plans.len(), plans.misses(), plans.hits()), (2, 2, 1));
}

#[test]
fn a_failed_recompile_keeps_the_current_plan() {
    let mut compiled = CompiledGraph::new(graph(), &at((64, 32))).unwrap();
    // Wider than the WebGPU defaults' largest 2D texture (8192).
    let errors = compiled
        .recompile(&at((10_000, 32)), &Features::new())
        .expect_err("too wide for the profile");
    assert!(errors.to_string().contains("\"target\""), "{errors}");
    assert_eq!(compiled.plan().output_size, (64, 32));
}

#[test]
fn the_graph_comes_back_unbound_and_compiles_again() {
    let compiled = CompiledGraph::new(graph(), &at((64, 32))).unwrap();
    assert_eq!(compiled.graph().passes().len(), 1);
    let graph = compiled.into_graph();
    assert_eq!(graph.compile(&at((8, 8))).unwrap().output_size, (8, 8));
}
