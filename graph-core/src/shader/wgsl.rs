//! Loading a WGSL shader: naga parses and validates it once, and plugins reflect on the
//! result at graph-load time and compile the same source on the device at execution.

use std::path::Path;
use std::sync::Arc;

use naga::valid::{Capabilities, ModuleInfo, ValidationFlags, Validator};
use wgpu_types::Features;

use super::error::ShaderError;
use super::parsed::Parsed;
use crate::position::Position;
use crate::{bounded_read, embedded};

/// A WGSL module that naga parsed and validated with its default capabilities (those of
/// WebGPU plus multisampled shading), which is what wgpu checks again at pipeline creation.
/// Immutable: clones share the parse, and parsing a text parsed before in the process
/// returns that parse (`parsed.rs`).
#[derive(Clone, Debug)]
pub struct Shader(Arc<Parse>);

#[derive(Debug)]
struct Parse {
    path: String,
    source: String,
    module: naga::Module,
    info: ModuleInfo,
}

impl Shader {
    /// Reads and validates the WGSL file at `path` (a regular file of at most
    /// [`bounded_read::MAX_SHADER_BYTES`]; a built-in file when a relative `path` is not on
    /// disk, see [`embedded`]); messages name it as given.
    pub fn load(path: impl AsRef<Path>) -> Result<Shader, ShaderError> {
        let path = path.as_ref();
        let shown = path.display().to_string();
        match embedded::read_text(path, bounded_read::MAX_SHADER_BYTES) {
            Ok(source) => Shader::parse(shown, source),
            Err(e) => Err(ShaderError::Unreadable {
                path: shown,
                reason: e.to_string(),
            }),
        }
    }

    /// Validates WGSL `source`; `path` names it in messages.
    pub fn parse(
        path: impl Into<String>,
        source: impl Into<String>,
    ) -> Result<Shader, ShaderError> {
        Self::parse_for(path, source, Features::empty())
    }

    /// Validates WGSL `source` that may use what the optional device `features` allow
    /// in shaders (64-bit integers and their atomics); a pass using such a shader runs
    /// only where the device has them (see [`DEVICE_CONDITIONS`](crate::DEVICE_CONDITIONS)).
    pub fn parse_for(
        path: impl Into<String>,
        source: impl Into<String>,
        features: Features,
    ) -> Result<Shader, ShaderError> {
        let source: String = source.into();
        // A byte-order mark from a Windows editor is invisible there, and not WGSL.
        let source = match source.strip_prefix('\u{feff}') {
            Some(rest) => rest.to_owned(),
            None => source,
        };
        static PARSED: Parsed<Shader> = Parsed::new();
        PARSED.get(path.into(), source, features, |path, source| {
            Self::parse_and_validate(path, source, features)
        })
    }

    /// Parses and validates `source`, as [`parse_for`](Self::parse_for) says.
    fn parse_and_validate(
        path: String,
        source: String,
        features: Features,
    ) -> Result<Shader, ShaderError> {
        let module = naga::front::wgsl::parse_str(&source).map_err(|e| {
            invalid(
                &path,
                &source,
                e.location(&source),
                e.message().to_owned(),
                e.emit_to_string_with_path(&source, &path),
            )
        })?;
        let info = Validator::new(ValidationFlags::all(), capabilities(features))
            .validate(&module)
            .map_err(|e| {
                invalid(
                    &path,
                    &source,
                    e.location(&source),
                    with_causes(e.as_inner()),
                    e.emit_to_string_with_path(&source, &path),
                )
            })?;
        Ok(Shader(Arc::new(Parse {
            path,
            source,
            module,
            info,
        })))
    }

    /// The path the shader was loaded from, as given.
    pub fn path(&self) -> &str {
        &self.0.path
    }

    /// The WGSL text, for creating the device's shader module.
    pub fn source(&self) -> &str {
        &self.0.source
    }

    /// naga's module, validated: what reflection reads.
    pub fn module(&self) -> &naga::Module {
        &self.0.module
    }

    /// naga's validation results, which say what each entry point uses.
    pub fn info(&self) -> &ModuleInfo {
        &self.0.info
    }
}

fn invalid(
    path: &str,
    source: &str,
    location: Option<naga::SourceLocation>,
    message: String,
    report: String,
) -> ShaderError {
    ShaderError::Invalid {
        path: path.to_owned(),
        // Whole-module errors (no span) are reported at the top of the file.
        at: location.map_or(Position::START, |l| {
            Position::of_offset(source, l.offset as usize)
        }),
        message,
        report,
    }
}

/// A validation error's own message says which function failed; its causes say why.
fn with_causes(error: &dyn std::error::Error) -> String {
    let mut message = error.to_string();
    let mut cause = error.source();
    while let Some(c) = cause {
        message.push_str(": ");
        message.push_str(&c.to_string());
        cause = c.source();
    }
    message
}

/// What naga allows a shader for the device `features` that widen WGSL.
fn capabilities(features: Features) -> Capabilities {
    let mut capabilities = Capabilities::default();
    for (feature, capability) in [
        (Features::SHADER_INT64, Capabilities::SHADER_INT64),
        (
            Features::SHADER_INT64_ATOMIC_MIN_MAX,
            Capabilities::SHADER_INT64_ATOMIC_MIN_MAX,
        ),
    ] {
        capabilities.set(capability, features.contains(feature));
    }
    capabilities
}
