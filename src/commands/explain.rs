//! `rgraph explain`: the compiled plan of a graph file, for people or tools.

use std::path::Path;

use graph_core::explain;
use graph_core::file::load_file;

use super::target::compile_options;
use super::CommandError;
use crate::cli::{Format, Target};
use crate::registry::registry;

pub fn run(pipeline: &Path, format: Format, target: &Target) -> Result<(), CommandError> {
    let options = compile_options(target)?;
    let plan = load_file(pipeline, &registry())
        .and_then(|loaded| loaded.compile(&options))
        .map_err(|errors| {
            println!("{errors}");
            CommandError::Invalid(format!("{} is invalid", pipeline.display()))
        })?;
    let text = match format {
        Format::Text => explain::text(&plan),
        Format::Dot => explain::dot(&plan),
        Format::Json => explain::json(&plan),
    };
    print!("{text}");
    Ok(())
}
