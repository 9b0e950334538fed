//! Command-line interface: what each command takes, with help that teaches.

use std::path::PathBuf;

use clap::{Parser, Subcommand, ValueEnum};

#[derive(Parser)]
#[command(
    name = "rgraph",
    version,
    about = "A render graph on wgpu: RON pipelines checked without a GPU, deferred shading with MSAA",
    long_about = "rgraph compiles render graphs declared in RON files (see pipelines/) into plans: \
                  pass order, culled passes with reasons, texture lifetimes, usages, load/store \
                  operations and pooled memory. Validation and explanation need no GPU; rendering \
                  runs headless on any Vulkan adapter, lavapipe included.",
    after_help = "Examples:\n  rgraph validate pipelines/*.ron shaders/*.wgsl\n  rgraph explain --pipeline pipelines/postprocess_demo.ron --format dot | dot -Tpng > plan.png\n  rgraph adapters"
)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Subcommand)]
pub enum Command {
    /// Check graph files (.ron) and shaders (.wgsl) without a GPU.
    ///
    /// Exit status: 0 when every file is valid, 1 when any is not (each problem printed as
    /// FILE:LINE:COL: error: MESSAGE), 2 for usage or I/O errors.
    Validate {
        /// Graph files (.ron) or WGSL shaders (.wgsl).
        #[arg(required = true, value_name = "FILE")]
        files: Vec<PathBuf>,
        #[command(flatten)]
        target: Target,
    },
    /// Print the compiled plan of a graph file: order, lifetimes, usages, load/store,
    /// physical textures and memory, culled passes with the reason. No GPU needed.
    Explain {
        /// The graph file.
        #[arg(long, value_name = "FILE")]
        pipeline: PathBuf,
        /// text for people, dot for Graphviz (culled parts grey), json for tools.
        #[arg(long, value_enum, default_value_t = Format::Text)]
        format: Format,
        #[command(flatten)]
        target: Target,
    },
    /// List the GPU adapters wgpu can use, with their features and sample counts.
    Adapters {
        /// Also write the profile (limits, features, format capabilities) of the adapter
        /// picked by --adapter to this JSON file, for `--profile FILE` on machines without it.
        #[arg(long, value_name = "FILE")]
        save_profile: Option<PathBuf>,
        /// Adapter for --save-profile: lavapipe, gpu, or part of an adapter's name
        /// (default: $RGRAPH_ADAPTER, else lavapipe).
        #[arg(long)]
        adapter: Option<String>,
    },
}

/// What the graph is compiled for.
#[derive(clap::Args)]
pub struct Target {
    /// Device limits and formats to validate against: `webgpu` (the defaults every device
    /// has), `adapter` (the adapter picked by --adapter / RGRAPH_ADAPTER), or a profile
    /// file (.json) written by `rgraph adapters --save-profile`.
    #[arg(long, default_value = "webgpu", value_name = "webgpu|adapter|FILE")]
    pub profile: String,
    /// The output size relative texture sizes resolve against.
    #[arg(long, default_value = "1920x1080", value_parser = parse_size, value_name = "WxH")]
    pub size: (u32, u32),
    /// Adapter for `--profile adapter`: lavapipe, gpu, or part of an adapter's name
    /// (default: $RGRAPH_ADAPTER, else lavapipe).
    #[arg(long)]
    pub adapter: Option<String>,
}

#[derive(Copy, Clone, PartialEq, Eq, ValueEnum)]
pub enum Format {
    Text,
    Dot,
    Json,
}

/// Parses `WIDTHxHEIGHT` with both at least 1.
pub fn parse_size(text: &str) -> Result<(u32, u32), String> {
    let (w, h) = text
        .split_once(['x', 'X'])
        .ok_or_else(|| format!("expected WIDTHxHEIGHT, e.g. 1280x720, got \"{text}\""))?;
    let parse = |s: &str, what: &str| {
        s.trim()
            .parse::<u32>()
            .map_err(|_| format!("{what} \"{s}\" is not a whole number"))
            .and_then(|v| {
                if v == 0 {
                    Err(format!("{what} must be at least 1"))
                } else {
                    Ok(v)
                }
            })
    };
    Ok((parse(w, "width")?, parse(h, "height")?))
}
