//! Why a render failed, and which exit status that earns: 1 when the inputs were read and
//! are wrong (pipeline, scene, view, a pass failing on the device), 2 for usage, I/O and
//! adapter problems.

use std::path::PathBuf;

use crate::commands::CommandError;
use crate::frame::FrameError;
use rgraph_passes::FrameInputsError;

#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    #[error("{0}")]
    Frame(#[from] FrameError),

    #[error("--view {view}: {pipeline} has no output \"{output}\"; its views: {offered}")]
    UnknownView {
        view: String,
        pipeline: PathBuf,
        output: String,
        offered: String,
    },

    /// A problem with `--out`, or writing it.
    #[error("{0}")]
    Output(String),

    /// `--time` that does not fit `--frames`.
    #[error("{0}")]
    Time(String),

    /// A frame's inputs (the orbited camera, the posed meshes) that the scene refused.
    #[error("{0}")]
    FrameInputs(#[from] FrameInputsError),
}

impl RenderError {
    /// Reports the error the way the other commands do: invalid inputs are printed here
    /// (exit 1), usage problems by `main` (exit 2).
    pub fn into_command_error(self) -> CommandError {
        let usage = match &self {
            RenderError::Frame(frame) => frame.is_usage(),
            RenderError::Output(_) | RenderError::Time(_) => true,
            RenderError::UnknownView { .. } | RenderError::FrameInputs(_) => false,
        };
        if usage {
            return CommandError::Usage(self.to_string());
        }
        match &self {
            RenderError::Frame(FrameError::Pipeline(errors)) => eprintln!("{errors}"),
            other => eprintln!("error: {other}"),
        }
        CommandError::Invalid(self.to_string())
    }
}
