//! Why loading, compiling, running or reading a frame failed, naming the pipeline (and
//! the scene, output or pass) at fault.

use std::path::{Path, PathBuf};

use rgraph_core::file::{FileErrors, NotAnOutput};
use rgraph_core::gpu::{DeviceError, ExecuteError, ReadbackError};
use rgraph_scene::SceneError;

#[derive(Debug, thiserror::Error)]
pub enum FrameError {
    /// Every line already reads `FILE:LINE:COL: error: MESSAGE`.
    #[error("{0}")]
    Pipeline(FileErrors),

    #[error("--pipeline {path}: cannot read the file: {reason}")]
    PipelineUnreadable { path: PathBuf, reason: String },

    /// Names the file (or built-in scene) and the object at fault.
    #[error("{0}")]
    Scene(SceneError),

    #[error("{pipeline}: {source}")]
    NotAnOutput {
        pipeline: PathBuf,
        source: NotAnOutput,
    },

    #[error(
        "output \"{output}\" of {pipeline} is {found}; only rgba8unorm-srgb (or rgba8unorm) \
         textures the graph creates can be read back as 8-bit images"
    )]
    Unreadable {
        output: String,
        pipeline: PathBuf,
        found: String,
    },

    #[error(
        "output \"{output}\" of {pipeline} is not made for this scene: {why} (features: \
         {features}); --no-specialise renders the pipeline as for a scene using every feature"
    )]
    NotForScene {
        output: String,
        pipeline: PathBuf,
        why: String,
        features: String,
    },

    #[error(
        "--exposure auto: {pipeline} has no auto_exposure pass that runs for this output \
         (the pipelines in pipelines/ meter the frame under the condition auto_exposure)"
    )]
    NoMetering { pipeline: PathBuf },

    #[error(
        "--background {background}: {pipeline} has no background pass that runs for this \
         output (pipelines/visibility_msaa_4x.ron, the default, draws one under the \
         condition background)"
    )]
    NoBackground {
        pipeline: PathBuf,
        background: String,
    },

    #[error(
        "--background environment: scene {scene} has no environment (its file brings its own \
         lights; the environment is the default lighting of files without them): give \
         --background color:R,G,B or transparent"
    )]
    NoEnvironment { scene: String },

    #[error(
        "{pipeline} imports \"{resource}\", which an engine binds; the command line runs \
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

    /// A scene texture larger than the device's largest 2D texture.
    #[error(
        "{scene}: texture {texture} is {width}x{height}, larger than {max}, the largest 2D \
         texture of {adapter}"
    )]
    SceneTextureTooLarge {
        scene: String,
        texture: String,
        width: u32,
        height: u32,
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
}

impl FrameError {
    /// An output that cannot become 8-bit texels, because it is `found`.
    pub fn unreadable(output: &str, pipeline: &Path, found: impl Into<String>) -> Self {
        FrameError::Unreadable {
            output: output.to_string(),
            pipeline: pipeline.to_path_buf(),
            found: found.into(),
        }
    }

    /// Problems of the environment or of how the command was called (an unreadable file,
    /// a missing adapter, a size the device lacks), rather than of the inputs' contents.
    pub fn is_usage(&self) -> bool {
        matches!(
            self,
            FrameError::PipelineUnreadable { .. }
                | FrameError::TooLarge { .. }
                | FrameError::SceneTextureTooLarge { .. }
                | FrameError::Device(_)
                | FrameError::Scene(SceneError::Io { .. })
        )
    }
}
