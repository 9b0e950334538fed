//! Helpers shared by the compile tests: compiling against the WebGPU defaults and pulling
//! out the one error a broken graph is expected to report.

use rgraph_core::types::TextureFormat;
use rgraph_core::{
    ColorLoad, CompileOptions, Graph, GraphBuilder, GraphError, Plan, Size, TextureDesc,
    TextureHandle,
};

pub const CLEAR: ColorLoad = ColorLoad::Clear([0.0; 4]);

/// A single-sampled 64x64 texture: small enough that byte counts stay readable.
pub fn tex(format: TextureFormat) -> TextureDesc {
    TextureDesc::new(format).size(Size::Absolute(64, 64))
}

/// Compiles at 1920x1080 against the WebGPU defaults, expecting success.
pub fn plan(graph: &Graph) -> Plan {
    graph
        .compile(&CompileOptions::default())
        .unwrap_or_else(|e| panic!("expected the graph to compile, got:\n{e}"))
}

/// Compiles against the WebGPU defaults, expecting failure, and returns every error.
pub fn errors(graph: &Graph) -> Vec<GraphError> {
    errors_with(graph, &CompileOptions::default())
}

pub fn errors_with(graph: &Graph, options: &CompileOptions) -> Vec<GraphError> {
    match graph.compile(options) {
        Ok(_) => panic!("expected the graph to be rejected"),
        Err(e) => e.0,
    }
}

/// The one error the graph is expected to report.
pub fn only_error(graph: &Graph) -> GraphError {
    let mut errors = errors(graph);
    assert_eq!(
        errors.len(),
        1,
        "expected exactly one error, got {errors:#?}"
    );
    errors.remove(0)
}

/// A render pass called `name` that clears `target` and keeps the result past the frame,
/// so it is never culled: the smallest live pass a test can add.
pub fn clear_pass(g: &mut GraphBuilder, name: &str, target: TextureHandle) -> TextureHandle {
    let out = g.add_render_pass(name).color_output(target, CLEAR);
    g.export(out);
    out
}
