//! `rgraph validate`: graph files compiled and shaders checked, without a GPU.

use std::path::{Path, PathBuf};

use graph_core::file::{validate_file, validate_shader, ErrorKind, FileErrors};
use graph_core::CompileOptions;

use super::target::compile_options;
use super::CommandError;
use crate::cli::Target;
use crate::registry::registry;

pub fn run(files: &[PathBuf], target: &Target) -> Result<(), CommandError> {
    let options = compile_options(target)?;
    let registry = registry();
    let mut invalid = 0;
    for file in files {
        let errors = match file.extension().and_then(|e| e.to_str()) {
            Some("wgsl") => validate_shader(file).err(),
            Some("ron") => validate_file(file, &registry, &options).err(),
            _ => {
                return Err(CommandError::Usage(format!(
                    "{}: not a graph file (.ron) or shader (.wgsl)",
                    file.display()
                )))
            }
        };
        match errors {
            None => eprintln!("{}: ok", file.display()),
            Some(errors) if is_unreadable(file, &errors) => {
                let reason = errors
                    .0
                    .iter()
                    .map(|e| e.kind.to_string())
                    .collect::<Vec<_>>();
                return Err(CommandError::Usage(format!(
                    "{}: {}",
                    file.display(),
                    reason.join("; ")
                )));
            }
            Some(errors) => {
                invalid += 1;
                println!("{errors}");
            }
        }
    }
    report(invalid, files.len(), &options)
}

/// The file itself could not be read: an I/O problem (exit 2), not an invalid file.
fn is_unreadable(file: &Path, errors: &FileErrors) -> bool {
    errors.0.iter().any(|e| {
        matches!(e.kind, ErrorKind::Unreadable { .. }) && Path::new(&e.location.path) == file
    })
}

fn report(invalid: usize, total: usize, options: &CompileOptions) -> Result<(), CommandError> {
    if invalid == 0 {
        eprintln!(
            "{total} file(s) valid for {} at {}x{}",
            options.profile.name, options.output_size.0, options.output_size.1
        );
        Ok(())
    } else {
        Err(CommandError::Invalid(format!(
            "{invalid} of {total} file(s) invalid"
        )))
    }
}
