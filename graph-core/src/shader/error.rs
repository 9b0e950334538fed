//! Why a shader could not be used.

use thiserror::Error;

use crate::position::Position;

/// A WGSL file that could not be read, or that naga rejects.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub enum ShaderError {
    #[error("cannot read shader \"{path}\": {reason}")]
    Unreadable { path: String, reason: String },

    /// `at` is where naga points; its full report (source excerpt and notes) is `report`.
    #[error("{path}:{at}: {message}")]
    Invalid {
        path: String,
        at: Position,
        message: String,
        report: String,
    },
}

impl ShaderError {
    /// The shader file the error is about.
    pub fn path(&self) -> &str {
        match self {
            ShaderError::Unreadable { path, .. } | ShaderError::Invalid { path, .. } => path,
        }
    }
}
