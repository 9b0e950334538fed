//! Why a row could not be measured (it becomes an error row, naming the scene and the
//! pipeline), and why a whole bench failed.

use std::path::PathBuf;

use rgraph_scene::SceneError;

use crate::commands::CommandError;
use crate::frame::FrameError;

/// One row's failure; the other rows are still measured.
#[derive(Debug, thiserror::Error)]
pub enum RowError {
    #[error("scene {scene}: {source}")]
    Scene { scene: String, source: SceneError },

    #[error("{pipeline} on {scene}: {source}")]
    Frame {
        pipeline: String,
        scene: String,
        source: FrameError,
    },
}

/// The bench as a whole failed.
#[derive(Debug, thiserror::Error)]
pub enum BenchError {
    #[error("{0}")]
    Device(FrameError),

    #[error("--out-dir {path}: {reason}")]
    OutDir { path: PathBuf, reason: String },

    #[error("cannot write {path}: {reason}")]
    Write { path: PathBuf, reason: String },

    #[error("--motion on {scene}: {why}")]
    Motion { scene: String, why: String },

    #[error("nothing could be measured: all {rows} rows are errors (see {results})")]
    NothingMeasured { rows: usize, results: PathBuf },
}

impl From<BenchError> for CommandError {
    /// Nothing measured means the inputs were wrong (exit 1, printed here); the rest are
    /// usage, I/O and adapter problems (exit 2, printed by `main`).
    fn from(error: BenchError) -> CommandError {
        match error {
            BenchError::NothingMeasured { .. } => {
                eprintln!("error: {error}");
                CommandError::Invalid(error.to_string())
            }
            other => CommandError::Usage(other.to_string()),
        }
    }
}
