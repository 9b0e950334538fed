//! The window's event handling: frames, the orbit camera, the scene's animation, the view
//! picker, hot reload and the title.

use std::path::PathBuf;
use std::sync::Arc;
use std::time::{Duration, Instant};

use image::RgbaImage;
use rgraph_passes::{FrameInputs, Host};
use rgraph_scene::glam::DVec3;
use winit::application::ApplicationHandler;
use winit::dpi::PhysicalSize;
use winit::event::{ElementState, KeyEvent, MouseButton, WindowEvent};
use winit::event_loop::{ActiveEventLoop, ControlFlow};
use winit::keyboard::{Key, NamedKey};
use winit::window::{Window, WindowId};

use super::playback::Playback;
use super::present::Presenter;
use super::title::{cycle, title};
use super::watch::Watch;
use super::{Loader, Shown, ViewError};
use crate::cli::ViewArgs;
use crate::frame::FrameError;

/// Radians an arrow key turns the camera.
const KEY_TURN: f64 = 5.0 * std::f64::consts::PI / 180.0;
/// Radians a pixel of horizontal drag turns the camera.
const DRAG_TURN: f64 = 0.4 * std::f64::consts::PI / 180.0;
/// How often the title's times are refreshed (a new title every frame would flicker).
const TITLE_EVERY: Duration = Duration::from_millis(250);

/// The viewer's state between events. The graph on screen (`shown`) is only ever replaced
/// by one that loaded, compiled and ran its first frame.
pub struct Viewer<'s> {
    loader: Loader<'s>,
    shown: Shown<'s>,
    /// `None` until the event loop resumes and the window exists.
    presenter: Option<Presenter>,
    initial_size: (u32, u32),
    /// The size the last load was for: a window size is tried once, so a size the
    /// device refuses is reported once rather than every frame.
    loaded_size: (u32, u32),
    watch: Watch,
    poll_every: Duration,
    polled_at: Instant,
    camera: Orbit,
    /// The scene's first animation, posing every frame; `None` without one.
    playback: Option<Playback>,
    /// Whether the left button is held: moving the cursor then turns the camera.
    dragging: bool,
    /// The cursor's last x in the window.
    cursor_x: f64,
    shift: bool,
    /// The first line of the last failed reload, until a reload succeeds.
    error: Option<String>,
    /// Frames still to present with `--frames`.
    frames_left: Option<u32>,
    screenshot: Option<PathBuf>,
    last_image: Option<RgbaImage>,
    presented_at: Option<Instant>,
    frame_ms: f64,
    title_at: Option<Instant>,
    /// What stopped the viewer, returned by [`Viewer::finish`].
    failure: Option<ViewError>,
}

impl<'s> Viewer<'s> {
    /// `camera`: the orbit the host's frame inputs are at now.
    pub fn new(loader: Loader<'s>, shown: Shown<'s>, camera: Orbit, args: &ViewArgs) -> Viewer<'s> {
        let watch = Watch::new(&loader.path);
        let playback = Playback::first(&loader.host.scene);
        Viewer {
            loader,
            shown,
            presenter: None,
            initial_size: args.frame.size(),
            loaded_size: args.frame.size(),
            watch,
            poll_every: Duration::from_millis(args.poll_ms),
            polled_at: Instant::now(),
            playback,
            camera,
            dragging: false,
            cursor_x: 0.0,
            shift: false,
            error: None,
            frames_left: args.frames,
            screenshot: args.screenshot.clone(),
            last_image: None,
            presented_at: None,
            frame_ms: 0.0,
            title_at: None,
            failure: None,
        }
    }

    /// After the event loop: the failure that stopped it, else the screenshot written.
    pub fn finish(self) -> Result<(), ViewError> {
        if let Some(failure) = self.failure {
            return Err(failure);
        }
        if let (Some(path), Some(image)) = (&self.screenshot, &self.last_image) {
            super::output::write_png(path, image)?;
            eprintln!("screenshot {}", path.display());
        }
        Ok(())
    }

    fn fail(&mut self, event_loop: &ActiveEventLoop, failure: ViewError) {
        self.failure = Some(failure);
        event_loop.exit();
    }

    /// One frame: reload first when a watched file changed or the window's size did
    /// (the reload runs the frame), else run the graph on screen; then present it.
    fn frame(&mut self, event_loop: &ActiveEventLoop) -> Result<(), ViewError> {
        let Some(size) = self.presenter.as_ref().map(Presenter::size) else {
            return Ok(());
        };
        let mut reason = None;
        if self.polled_at.elapsed() >= self.poll_every {
            self.polled_at = Instant::now();
            reason = self
                .watch
                .changed()
                .map(|file| format!("{} changed", file.display()));
        }
        if reason.is_none() && self.loaded_size != size {
            reason = Some(format!("the window is {}x{}", size.0, size.1));
        }
        // Posed before a reload too, which runs the frame itself.
        if let Some(playback) = &self.playback {
            let host = &self.loader.host;
            host.set_frame(playback.pose(&host.scene, self.camera.inputs()))?;
        }
        let reloaded = match reason {
            Some(reason) => self.reload(&self.shown.output.clone(), size, &reason),
            None => false,
        };
        if !reloaded {
            self.shown.report = self.shown.prepared.run(1)?.remove(0);
        }
        let last = self.frames_left == Some(1);
        let read = last && self.screenshot.is_some();
        let texture = self.shown.prepared.texture(&self.shown.output)?;
        let presenter = self.presenter.as_mut().expect("checked above");
        let image = presenter.present(&self.loader.session.gpu, texture, read)?;
        if image.is_some() {
            self.last_image = image;
        }
        let now = Instant::now();
        if let Some(before) = self.presented_at.replace(now) {
            self.frame_ms = (now - before).as_secs_f64() * 1e3;
        }
        if self.title_at.is_none_or(|t| t.elapsed() >= TITLE_EVERY) {
            self.update_title();
        }
        if let Some(left) = &mut self.frames_left {
            // A screenshot frame the surface skipped is tried again.
            if !read || self.last_image.is_some() {
                *left -= 1;
            }
            if *left == 0 {
                event_loop.exit();
            }
        }
        Ok(())
    }

    /// Loads the graph for `output` at `size`; on success it replaces the graph on screen
    /// (and has run this frame), on failure the errors go to stderr and their first line
    /// to the title, and the last good graph stays. Returns whether it replaced it.
    fn reload(&mut self, output: &str, size: (u32, u32), reason: &str) -> bool {
        let started = Instant::now();
        self.loaded_size = size;
        // What the files name now (an edit may change that, valid or not), stamped before
        // they are read, so an edit saved while loading is seen at the next poll.
        self.watch = Watch::new(&self.loader.path);
        // The old graph (and its plugins) is dropped only when the new one succeeds.
        match self.loader.load(output, size) {
            Ok(shown) => {
                self.shown = shown;
                self.error = None;
                eprintln!(
                    "reloaded {} ({reason}) in {:.0} ms: showing {}",
                    self.loader.path.display(),
                    started.elapsed().as_secs_f64() * 1e3,
                    self.position_text()
                );
                self.update_title();
                true
            }
            Err(error) => {
                report(&error);
                eprintln!("reload failed ({reason}): the last good graph keeps running");
                self.error = error.to_string().lines().next().map(str::to_string);
                self.update_title();
                false
            }
        }
    }

    /// "VIEW (i/n)" of the graph on screen.
    fn position_text(&self) -> String {
        let (index, count) = self.position();
        format!("{} ({}/{count})", self.shown.output, index + 1)
    }

    fn position(&self) -> (usize, usize) {
        let views = &self.shown.views;
        let index = views
            .iter()
            .position(|v| *v == self.shown.output)
            .unwrap_or(0);
        (index, views.len())
    }

    fn update_title(&mut self) {
        let Some(presenter) = &self.presenter else {
            return;
        };
        let text = title(
            &self.loader.path,
            &self.shown.output,
            self.position(),
            self.camera.angle.to_degrees(),
            &self.shown.report,
            self.frame_ms,
            self.error.as_deref(),
        );
        presenter.window().set_title(&text);
        self.title_at = Some(Instant::now());
    }

    /// Shows the view `step` places away (1 next, -1 previous) in the file's views.
    fn pick(&mut self, step: isize) {
        let (index, count) = self.position();
        let Some(output) = self.shown.views.get(cycle(index, count, step)).cloned() else {
            return;
        };
        if let Some(size) = self.presenter.as_ref().map(Presenter::size) {
            self.reload(&output, size, "view picked");
        }
    }

    fn turn(&mut self, radians: f64) -> Result<(), ViewError> {
        self.camera.angle += radians;
        self.loader.host.set_frame(self.camera.inputs())?;
        Ok(())
    }

    fn key(&mut self, event_loop: &ActiveEventLoop, event: &KeyEvent) -> Result<(), ViewError> {
        if event.state != ElementState::Pressed {
            return Ok(());
        }
        let step = if self.shift { -1 } else { 1 };
        match &event.logical_key {
            Key::Named(NamedKey::ArrowLeft) => self.turn(-KEY_TURN)?,
            Key::Named(NamedKey::ArrowRight) => self.turn(KEY_TURN)?,
            Key::Named(NamedKey::Tab) => self.pick(step),
            Key::Named(NamedKey::Escape) => event_loop.exit(),
            Key::Character(c) => match c.to_lowercase().as_str() {
                "v" => self.pick(step),
                "r" => {
                    if let Some(size) = self.presenter.as_ref().map(Presenter::size) {
                        self.reload(&self.shown.output.clone(), size, "R pressed");
                    }
                }
                "q" => event_loop.exit(),
                _ => {}
            },
            _ => {}
        }
        Ok(())
    }

    fn event(&mut self, event_loop: &ActiveEventLoop, event: WindowEvent) -> Result<(), ViewError> {
        match event {
            WindowEvent::CloseRequested => event_loop.exit(),
            WindowEvent::Resized(size) => {
                if let Some(presenter) = &mut self.presenter {
                    presenter.resize(&self.loader.session.gpu.device, (size.width, size.height));
                }
            }
            WindowEvent::ModifiersChanged(modifiers) => self.shift = modifiers.state().shift_key(),
            WindowEvent::KeyboardInput { event, .. } => self.key(event_loop, &event)?,
            WindowEvent::MouseInput {
                state,
                button: MouseButton::Left,
                ..
            } => self.dragging = state == ElementState::Pressed,
            WindowEvent::CursorMoved { position, .. } => {
                let from = std::mem::replace(&mut self.cursor_x, position.x);
                if self.dragging {
                    self.turn((position.x - from) * DRAG_TURN)?;
                }
            }
            WindowEvent::RedrawRequested => self.frame(event_loop)?,
            _ => {}
        }
        Ok(())
    }
}

impl ApplicationHandler for Viewer<'_> {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.presenter.is_some() {
            return;
        }
        event_loop.set_control_flow(ControlFlow::Poll);
        let (width, height) = self.initial_size;
        let attributes = Window::default_attributes()
            .with_title("rgraph view")
            .with_inner_size(PhysicalSize::new(width, height));
        let made = event_loop
            .create_window(attributes)
            .map_err(|e| ViewError::NoDisplay {
                reason: super::without_source_location(&e.to_string()),
                display: std::env::var("DISPLAY").ok(),
                wayland: std::env::var("WAYLAND_DISPLAY").ok(),
            })
            .and_then(|window| {
                let readable = self.screenshot.is_some();
                Presenter::new(&self.loader.session.gpu, Arc::new(window), readable)
            });
        match made {
            Ok(presenter) => {
                eprintln!(
                    "window {}x{}: showing {}; watching {}",
                    presenter.size().0,
                    presenter.size().1,
                    self.position_text(),
                    self.watch
                        .files()
                        .map(|f| f.display().to_string())
                        .collect::<Vec<_>>()
                        .join(", ")
                );
                self.presenter = Some(presenter);
                self.update_title();
            }
            Err(failure) => self.fail(event_loop, failure),
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _: WindowId, event: WindowEvent) {
        if let Err(failure) = self.event(event_loop, event) {
            self.fail(event_loop, failure);
        }
    }

    fn about_to_wait(&mut self, _: &ActiveEventLoop) {
        if let Some(presenter) = &self.presenter {
            presenter.window().request_redraw();
        }
    }
}

/// The camera turned about the vertical axis through the scene's bounds centre, as
/// `render --orbit` turns it.
pub struct Orbit {
    start: FrameInputs,
    center: DVec3,
    /// Radians turned from the start.
    angle: f64,
}

impl Orbit {
    /// `host`'s current frame inputs turned by `degrees`.
    pub fn of(host: &Host, degrees: f64) -> Orbit {
        Orbit {
            start: FrameInputs::clone(&host.frame()),
            center: host.scene.bounds.center(),
            angle: degrees.to_radians(),
        }
    }

    /// The frame inputs with the camera turned by the orbit's angle.
    pub fn inputs(&self) -> FrameInputs {
        FrameInputs {
            camera: self.start.camera.orbited(self.center, self.angle),
            ..self.start.clone()
        }
    }
}

/// A failed reload's errors on stderr: graph-file errors as their `FILE:LINE:COL: error:`
/// lines, anything else after `error: `.
fn report(error: &FrameError) {
    match error {
        FrameError::Pipeline(errors) => eprintln!("{errors}"),
        other => eprintln!("error: {other}"),
    }
}
