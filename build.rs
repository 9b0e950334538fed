//! Build-time validation: every graph file in `pipelines/` is loaded and compiled, and
//! every WGSL file in `shaders/` is validated by naga, all without a GPU. An invalid file
//! fails the build with `FILE:LINE:COL: error: MESSAGE` lines, as `rgraph validate` and
//! an engine's own build script (through `graph_core::file::validate_dir`) report them.

use graph_core::file::{validate_dir, Registry};
use graph_core::CompileOptions;

fn main() {
    println!("cargo:rerun-if-changed=pipelines");
    println!("cargo:rerun-if-changed=shaders");
    let mut registry = Registry::with_builtins();
    passes_deferred_msaa::register(&mut registry, None);
    // Graph files must fit every WebGPU device at 1080p; `rgraph validate --target`
    // checks them against other profiles and sizes.
    let options = CompileOptions::default();
    if let Err(errors) = validate_dir("pipelines", "shaders", &registry, &options) {
        // Cargo shows a failed build script's stderr under the failure, one error a line.
        eprintln!("{errors}");
        eprintln!(
            "{} error(s) in pipelines/ or shaders/ (validated for {} at {}x{})",
            errors.0.len(),
            options.profile.name,
            options.output_size.0,
            options.output_size.1
        );
        std::process::exit(1);
    }
}
