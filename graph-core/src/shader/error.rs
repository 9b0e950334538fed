//! Why a shader could not be used.

use thiserror::Error;

use crate::position::Position;

/// A WGSL file that could not be read, or that naga rejects.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub enum ShaderError {
    /// The file could not be read (missing, not a regular file, too large, not UTF-8).
    #[error("cannot read shader \"{path}\": {reason}")]
    Unreadable {
        /// The shader's path, as given.
        path: String,
        /// Why, in words.
        reason: String,
    },

    /// `at` is where naga points; its full report (source excerpt and notes) is `report`.
    #[error("{path}:{at}: {message}")]
    Invalid {
        /// The shader's path, as given.
        path: String,
        /// Line and column naga points at.
        at: Position,
        /// naga's one-line message.
        message: String,
        /// naga's full report: the source excerpt and notes.
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
