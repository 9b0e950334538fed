//! `rgraph validate`: graph files compiled and shaders checked, without a GPU.

use std::path::PathBuf;

use rgraph_core::file::{validate_file, validate_shader};
use rgraph_core::CompileOptions;

use super::target::compile_options;
use super::CommandError;
use crate::cli::Target;
use crate::registry::registry;

/// Checks every file, whatever the others give: a file that is not .ron or .wgsl, or
/// cannot be read, is reported on stderr (`error: FILE: REASON`) and the rest are still
/// checked; the exit status is then 2. Each invalid file's errors go to stdout.
pub fn run(files: &[PathBuf], target: &Target) -> Result<(), CommandError> {
    let options = compile_options(target)?;
    let registry = registry();
    let (mut invalid, mut unusable) = (0, 0);
    for file in files {
        let errors = match file.extension().and_then(|e| e.to_str()) {
            Some("wgsl") => validate_shader(file).err(),
            Some("ron") => validate_file(file, &registry, &options).err(),
            _ => {
                unusable += 1;
                eprintln!(
                    "error: {}: not a graph file (.ron) or shader (.wgsl)",
                    file.display()
                );
                continue;
            }
        };
        match errors {
            None => eprintln!("{}: ok", file.display()),
            Some(errors) if errors.is_unreadable(file) => {
                unusable += 1;
                let reasons = errors
                    .0
                    .iter()
                    .map(|e| e.kind.to_string())
                    .collect::<Vec<_>>();
                eprintln!("error: {}: {}", file.display(), reasons.join("; "));
            }
            Some(errors) => {
                invalid += 1;
                println!("{errors}");
            }
        }
    }
    report(invalid, unusable, files.len(), &options)
}

fn report(
    invalid: usize,
    unusable: usize,
    total: usize,
    options: &CompileOptions,
) -> Result<(), CommandError> {
    match (invalid, unusable) {
        (0, 0) => {
            eprintln!(
                "{total} file(s) valid for {} at {}x{}",
                options.profile.name, options.output_size.0, options.output_size.1
            );
            Ok(())
        }
        (_, 0) => Err(CommandError::Invalid(format!(
            "{invalid} of {total} file(s) invalid"
        ))),
        _ => Err(CommandError::Usage(format!(
            "{unusable} of {total} file(s) could not be checked, {invalid} invalid"
        ))),
    }
}
