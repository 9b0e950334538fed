//! `rgraph`: validate, explain and run render graphs from the command line.

mod cli;
mod commands;
mod frame;
mod registry;
mod vulkan_env;

use std::process::ExitCode;

use clap::Parser;

use cli::{Cli, Command};

/// `pipelines/`, `shaders/` and `bench/graphs/` as built (see build.rs): read when a
/// relative path to one of them is missing from disk.
static EMBEDDED: &[rgraph_core::embedded::EmbeddedFile] =
    include!(concat!(env!("OUT_DIR"), "/embedded.rs"));

fn main() -> ExitCode {
    rgraph_core::embedded::provide(EMBEDDED);
    let cli = Cli::parse();
    vulkan_env::prepare(&cli);
    registry::allow_graph_roots(cli.command.graph_roots());
    let result = match &cli.command {
        Command::Validate { files, target, .. } => commands::validate::run(files, target),
        Command::Explain {
            pipeline,
            scene,
            format,
            target,
            samples,
            assets,
            page,
            ..
        } => commands::explain::run(
            pipeline,
            scene.as_deref(),
            *format,
            target,
            samples,
            assets,
            page,
        ),
        Command::Render(args) => commands::render::run(args),
        Command::Bench(args) => commands::bench::run(args),
        Command::View(args) => commands::view::run(args),
        Command::Adapters {
            save_profile,
            adapter,
        } => commands::adapters::run(save_profile.as_deref(), adapter.as_deref()),
        Command::Compare {
            a,
            b,
            tolerance,
            at_least,
        } => commands::compare::run(a, b, *tolerance, *at_least),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            if let commands::CommandError::Usage(message) = &error {
                eprintln!("error: {message}");
            }
            error.exit_code()
        }
    }
}
