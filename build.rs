//! Build-time validation: every graph file in `pipelines/` is loaded and compiled, and
//! every WGSL file in `shaders/` is validated by naga, all without a GPU. An invalid file
//! fails the build with `FILE:LINE:COL: error: MESSAGE` lines, as `rgraph validate` and
//! an engine's own build script (through `rgraph_core::file::validate_dir`) report them.
//!
//! It also writes `$OUT_DIR/embedded.rs`: every `.ron` and `.wgsl` file of
//! [`EMBEDDED_DIRS`] as `(path, include_str!(..))`, which `main` provides to
//! `rgraph_core::embedded`.

use rgraph_core::file::{validate_dir, Registry};
use rgraph_core::CompileOptions;

/// The directories whose files the binary carries (see `rgraph_core::embedded`), so
/// `rgraph render` works from any directory: the default pipeline, the generic demos'
/// shaders, the bench's unique-surfaces graph.
const EMBEDDED_DIRS: [&str; 4] = ["pipelines", "pipelines/parts", "shaders", "bench/graphs"];

fn main() {
    for dir in EMBEDDED_DIRS {
        println!("cargo:rerun-if-changed={dir}");
    }
    write_embedded_list();
    let mut registry = Registry::with_builtins();
    rgraph_passes::register(&mut registry, None);
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

/// Writes `$OUT_DIR/embedded.rs`, a `&[(&str, &str)]` expression, sorted by path.
fn write_embedded_list() {
    let root = std::env::var("CARGO_MANIFEST_DIR").expect("cargo sets CARGO_MANIFEST_DIR");
    let mut paths: Vec<String> = EMBEDDED_DIRS
        .iter()
        .flat_map(|dir| {
            std::fs::read_dir(std::path::Path::new(&root).join(dir))
                .unwrap_or_else(|e| panic!("cannot list {dir}: {e}"))
                .filter_map(|entry| {
                    let name = entry.ok()?.file_name().into_string().ok()?;
                    let kept = name.ends_with(".ron") || name.ends_with(".wgsl");
                    kept.then(|| format!("{dir}/{name}"))
                })
                .collect::<Vec<_>>()
        })
        .collect();
    paths.sort();
    let entries: String = paths
        .iter()
        .map(|path| format!("    ({path:?}, include_str!(concat!(env!(\"CARGO_MANIFEST_DIR\"), \"/{path}\"))),\n"))
        .collect();
    let out = std::env::var("OUT_DIR").expect("cargo sets OUT_DIR");
    std::fs::write(
        std::path::Path::new(&out).join("embedded.rs"),
        format!("&[\n{entries}]\n"),
    )
    .unwrap_or_else(|e| panic!("cannot write embedded.rs: {e}"));
}
