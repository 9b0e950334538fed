//! Why a render failed, and which exit status that earns: 1 when the inputs were read and
//! are wrong (pipeline, scene, view, a pass failing on the device), 2 for usage, I/O and
//! adapter problems.

use std::path::{Path, PathBuf};

use graph_core::file::FileErrors;
use graph_core::gpu::{DeviceError, ExecuteError, ReadbackError};
use passes_deferred_msaa::scene::SceneError;

use crate::commands::CommandError;

#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// Every line already reads `FILE:LINE:COL: error: MESSAGE`.
    #[error("{0}")]
    Pipeline(FileErrors),

    #[error("--pipeline {path}: cannot read the file: {reason}")]
    PipelineUnreadable { path: PathBuf, reason: String },

    /// Names the file (or built-in scene) and the object at fault.
    #[error("{0}")]
    Scene(SceneError),

    #[error("--view {view}: {pipeline} has no output \"{output}\"; its views: {offered}")]
    UnknownView {
        view: String,
        pipeline: PathBuf,
        output: String,
        offered: String,
    },

    #[error(
        "output \"{output}\" of {pipeline} is {found}; render writes 8-bit PNGs from \
         rgba8unorm-srgb (or rgba8unorm) textures the graph creates"
    )]
    Unreadable {
        output: String,
        pipeline: PathBuf,
        found: String,
    },

    #[error(
        "{pipeline} imports \"{resource}\", which an engine binds; rgraph render runs \
         pipelines whose resources the graph creates"
    )]
    Imports { pipeline: PathBuf, resource: String },

    #[error(
        "--{flag} {value} is above {max}, the largest 2D texture of {adapter}; choose a \
         smaller size or another --adapter"
    )]
    TooLarge {
        flag: &'static str,
        value: u32,
        max: u32,
        adapter: String,
    },

    #[error("{0}")]
    Device(#[from] DeviceError),

    /// Names the pass when the device blamed one.
    #[error("{pipeline}: {source}")]
    Execute {
        pipeline: PathBuf,
        source: ExecuteError,
    },

    #[error("{pipeline}: reading back \"{output}\" failed: {source}")]
    Readback {
        pipeline: PathBuf,
        output: String,
        source: ReadbackError,
    },

    #[error("{pipeline}: device error after the frame:\n{messages}")]
    LateDevice { pipeline: PathBuf, messages: String },

    /// A problem with `--out`, or writing it.
    #[error("{0}")]
    Output(String),
}

impl RenderError {
    /// An output that cannot become PNG bytes, because it is `found`.
    pub fn unreadable(output: &str, pipeline: &Path, found: impl Into<String>) -> Self {
        RenderError::Unreadable {
            output: output.to_string(),
            pipeline: pipeline.to_path_buf(),
            found: found.into(),
        }
    }

    /// Reports the error the way the other commands do: invalid inputs are printed here
    /// (exit 1), usage problems by `main` (exit 2).
    pub fn into_command_error(self) -> CommandError {
        let usage = matches!(
            self,
            RenderError::PipelineUnreadable { .. }
                | RenderError::TooLarge { .. }
                | RenderError::Device(_)
                | RenderError::Output(_)
        ) || matches!(self, RenderError::Scene(SceneError::Io { .. }));
        if usage {
            return CommandError::Usage(self.to_string());
        }
        match &self {
            RenderError::Pipeline(errors) => eprintln!("{errors}"),
            other => eprintln!("error: {other}"),
        }
        CommandError::Invalid(self.to_string())
    }
}
