//! `rgraph view`: a pipeline shown live in a window, with an orbit camera, a view picker,
//! per-pass GPU times in the title, and hot reload of the graph file and its shaders.
//!
//! The same stages as `render` (scene, pipeline, device, compile), then a window whose
//! surface the chosen adapter draws into. Each frame runs the graph through one executor
//! (the camera moved through the host's frame inputs) and draws its output onto the
//! window. A changed watched file, another view or another window size loads the graph
//! again and runs its first frame; only when all of that succeeds does it replace the
//! graph on screen, so an invalid edit leaves the last good graph running.

mod app;
mod playback;
mod present;
mod title;
mod watch;

use std::path::PathBuf;
use std::sync::Arc;

use rgraph_core::file::GraphParams;
use rgraph_core::gpu::{AdapterChoice, FrameReport};
use rgraph_passes::{FrameInputsError, Host, Overrides};
use winit::event_loop::EventLoop;

use super::render::error::RenderError;
use super::render::{output, view};
use super::CommandError;
use crate::cli::{AssetArgs, ViewArgs};
use crate::frame::{host, FrameError, Pipeline, Prepared, Session, Specialise};

/// Why the viewer could not start or stopped.
#[derive(Debug, thiserror::Error)]
pub enum ViewError {
    /// The first load (or the scene, or the device): reported as `render` reports it.
    #[error("{0}")]
    Render(#[from] RenderError),

    #[error(
        "cannot open a window: {reason}. `rgraph view` needs a display: set DISPLAY (X11) \
         or WAYLAND_DISPLAY (Wayland) to a running display server (now DISPLAY={display:?}, \
         WAYLAND_DISPLAY={wayland:?}), or run it under a virtual one: `xvfb-run -a rgraph \
         view ...`; `rgraph render` needs none"
    )]
    NoDisplay {
        reason: String,
        display: Option<String>,
        wayland: Option<String>,
    },

    #[error("cannot draw into the window with adapter \"{adapter}\": {reason}; pick another with --adapter")]
    Surface { adapter: String, reason: String },

    #[error(
        "--screenshot: the window's surface cannot be read back (its textures allow \
         {usages}, not COPY_SRC)"
    )]
    Unreadable { usages: String },

    #[error("--screenshot: reading the presented image back failed: {0}")]
    Screenshot(String),

    /// A frame of the graph on screen failed on the device after its first one.
    #[error("{0}")]
    Frame(#[from] FrameError),

    #[error("{0}")]
    FrameInputs(#[from] FrameInputsError),

    #[error("the window's event loop failed: {0}")]
    EventLoop(#[from] winit::error::EventLoopError),
}

impl ViewError {
    /// Exit 1 for invalid inputs (printed here, as `render` does), 2 for usage, I/O,
    /// adapter and display problems.
    fn into_command_error(self) -> CommandError {
        match self {
            ViewError::Render(e) => e.into_command_error(),
            ViewError::Frame(e) => RenderError::Frame(e).into_command_error(),
            ViewError::FrameInputs(e) => RenderError::FrameInputs(e).into_command_error(),
            other => CommandError::Usage(other.to_string()),
        }
    }
}

/// Opens the window and runs until it is closed or `--frames` have been presented.
pub fn run(args: &ViewArgs) -> Result<(), CommandError> {
    view(args).map_err(ViewError::into_command_error)
}

fn view(args: &ViewArgs) -> Result<(), ViewError> {
    if let Some(path) = &args.screenshot {
        output::check(path, "--screenshot")?;
    }
    // The display first: without one nothing else is worth loading.
    let event_loop = EventLoop::new().map_err(|e| ViewError::NoDisplay {
        reason: without_source_location(&e.to_string()),
        display: std::env::var("DISPLAY").ok(),
        wayland: std::env::var("WAYLAND_DISPLAY").ok(),
    })?;

    eprintln!("load scene {}", args.frame.scene);
    let scene = (args.frame.assets)
        .load(&args.frame.scene)
        .map_err(|e| RenderError::Frame(FrameError::Scene(e)))?;
    for warning in AssetArgs::warnings(&args.frame.scene, &scene) {
        eprintln!("{warning}");
    }
    let overrides = Overrides {
        background: args.frame.background,
        shadows: args.frame.shadows.settings(),
        ..Overrides::default()
    };
    let host = host(Arc::new(scene), overrides);
    let choice = AdapterChoice::resolve(args.frame.adapter.as_deref());
    eprintln!("open device ({choice})");
    let session = Session::open(&choice).map_err(RenderError::Frame)?;
    let camera = app::Orbit::of(&host, args.orbit);
    host.set_frame(camera.inputs())?;
    let loader = Loader {
        session: &session,
        host,
        path: args.frame.pipeline.clone(),
        params: args.frame.samples.params(),
    };
    eprintln!("load pipeline {}", args.frame.pipeline.display());
    let output = view::output_name(&args.frame.view);
    let shown = loader
        .load(&output, args.frame.size())
        .map_err(|e| view::unknown(e, &args.frame.view))?;
    let mut viewer = app::Viewer::new(loader, shown, camera, args);
    event_loop.run_app(&mut viewer)?;
    viewer.finish()
}

/// winit's OS errors read `os error at FILE:LINE: WHY.`, FILE a path in the build
/// machine's cargo registry: only WHY means anything to a user (without its period: the
/// message goes on after it).
fn without_source_location(reason: &str) -> String {
    let why = match reason.strip_prefix("os error at ") {
        Some(rest) => rest.split_once(": ").map_or(rest, |(_, why)| why),
        None => reason,
    };
    why.trim_end_matches('.').to_owned()
}

/// Loads the pipeline for one view at one size on the session's device, with the
/// deferred plugins drawing the host's scene from its current frame inputs.
pub struct Loader<'s> {
    session: &'s Session,
    host: Arc<Host>,
    path: PathBuf,
    params: GraphParams,
}

/// A graph on screen: compiled for one output at one size, its first frame run.
pub struct Shown<'s> {
    prepared: Prepared<'s>,
    /// The output drawn on the window.
    output: String,
    /// The outputs the file declares that are views, "color" first: what the picker
    /// cycles through.
    views: Vec<String>,
    /// The last frame's report.
    report: FrameReport,
}

impl<'s> Loader<'s> {
    /// Loads, validates and compiles the file (specialised to the scene, as `render`
    /// does) keeping only `output`, and runs its first frame, so that a graph that fails
    /// anywhere up to its first frame is never shown.
    fn load(&self, output: &str, size: (u32, u32)) -> Result<Shown<'s>, FrameError> {
        let pipeline = Pipeline::load(
            &self.path,
            self.host.clone(),
            &[output],
            Specialise::ToScene,
            &self.params,
        )?;
        let views = view::viewable(pipeline.offered.iter().map(String::as_str))
            .into_iter()
            .map(String::from)
            .collect();
        let mut prepared = self.session.prepare(pipeline, size)?;
        let report = prepared.run(1)?.remove(0);
        Ok(Shown {
            prepared,
            output: output.to_string(),
            views,
            report,
        })
    }
}
