//! `rgraph view` on lavapipe under a virtual X display (Xvfb, started per test on a free
//! display): the presented image equals `rgraph render` of the same pipeline, scene and
//! size, hot reload picks up valid edits and reports invalid ones while the last good
//! graph keeps running, and without a display the command says what it needs.

use std::io::{BufRead, BufReader, Read};
use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::sync::mpsc::{channel, Receiver};
use std::time::{Duration, Instant};

use x11rb::connection::Connection as _;

use crate::cli_render_animation::sliding_cube;
use crate::cli_support::rgraph;

/// Where Debian's `xvfb` package installs the server.
const XVFB: &str = "/usr/bin/Xvfb";
/// Where Debian's `x11-utils` package installs the window lister the title is read with.
const XWININFO: &str = "/usr/bin/xwininfo";

/// A virtual X server on a display it picked itself (`-displayfd`), killed on drop.
struct Xvfb {
    child: Child,
    /// `:N`.
    display: String,
}

impl Xvfb {
    /// Starts Xvfb and waits until it accepts connections (it writes its display number
    /// then). A machine without it fails the test with the fix: these tests never skip.
    fn start() -> Xvfb {
        assert!(
            Path::new(XVFB).exists(),
            "the viewer tests need a virtual X server: apt-get install xvfb (.ci/run does)"
        );
        let mut child = Command::new(XVFB)
            .args([
                "-displayfd",
                "1",
                "-screen",
                "0",
                "640x480x24",
                "-nolisten",
                "tcp",
            ])
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .expect("Xvfb starts");
        let mut line = String::new();
        BufReader::new(child.stdout.take().expect("piped"))
            .read_line(&mut line)
            .expect("Xvfb writes its display number");
        let number = line.trim();
        assert!(
            !number.is_empty() && number.bytes().all(|b| b.is_ascii_digit()),
            "Xvfb gave no display number (got {line:?})"
        );
        Xvfb {
            child,
            display: format!(":{number}"),
        }
    }

    /// `rgraph ARGS` on this display (never on a Wayland one the environment names).
    fn rgraph(&self, args: &[&str]) -> Command {
        let mut command = Command::new(env!("CARGO_BIN_EXE_rgraph"));
        command
            .args(args)
            .current_dir(env!("CARGO_MANIFEST_DIR"))
            .env("DISPLAY", &self.display)
            .env("WINIT_X11_SCALE_FACTOR", "1")
            .env_remove("WAYLAND_DISPLAY");
        command
    }
}

impl Xvfb {
    /// Waits (up to a minute) until a window's title contains every one of `parts`, and
    /// returns the titles then, read with `xwininfo` (package x11-utils).
    fn wait_for_title(&self, parts: &[&str]) -> String {
        let deadline = Instant::now() + Duration::from_secs(60);
        loop {
            let out = Command::new(XWININFO)
                .args(["-display", &self.display, "-root", "-children"])
                .output()
                .unwrap_or_else(|e| panic!("{XWININFO} runs (apt-get install x11-utils): {e}"));
            let titles = String::from_utf8_lossy(&out.stdout).into_owned();
            let found = titles
                .lines()
                .any(|line| parts.iter().all(|part| line.contains(part)));
            if found {
                return titles;
            }
            assert!(
                Instant::now() < deadline,
                "no window title with {parts:?} within 60 s; the windows:\n{titles}"
            );
            std::thread::sleep(Duration::from_millis(100));
        }
    }
}

impl Drop for Xvfb {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

fn read_png(path: &Path) -> image::RgbaImage {
    image::open(path)
        .unwrap_or_else(|e| panic!("{} is not a readable PNG: {e}", path.display()))
        .into_rgba8()
}

/// Runs the viewer for 3 frames with a screenshot (`view_args` added) and renders the same
/// pipeline and scene at the window's size (`render_args` added, writing `--out DIR/out`;
/// the PNG compared is `DIR/rendered`): the two images must be equal byte for byte (the output is copied and
/// blitted onto the surface through non-sRGB views, so nothing is re-encoded on the way).
fn screenshot_equals_render(view_args: &[&str], render_args: &[&str], out: &str, rendered: &str) {
    let x = Xvfb::start();
    let dir = tempfile::tempdir().expect("a temporary directory");
    let shot = dir.path().join("shot.png");
    let size = ["--width", "160", "--height", "96"];
    let shot_arg = shot.to_str().expect("temp paths are UTF-8");
    let view = ["view", "--frames", "3", "--screenshot", shot_arg];
    let viewed = x
        .rgraph(&[&view[..], &size, view_args].concat())
        .output()
        .expect("rgraph runs");
    let stderr = String::from_utf8_lossy(&viewed.stderr);
    assert_eq!(
        viewed.status.code(),
        Some(0),
        "rgraph view failed:\n{stderr}"
    );
    assert!(stderr.contains("window 160x96"), "{stderr}");
    let out_arg = dir.path().join(out);
    let out_arg = out_arg.to_str().expect("temp paths are UTF-8");
    rgraph(&[&["render", "--out", out_arg][..], &size, render_args].concat()).expect(0);
    let (shot, reference) = (read_png(&shot), read_png(&dir.path().join(rendered)));
    assert_eq!(shot.dimensions(), reference.dimensions());
    let differing = shot
        .pixels()
        .zip(reference.pixels())
        .filter(|(a, b)| a != b)
        .count();
    assert_eq!(
        differing, 0,
        "{differing} pixels of the presented image differ from `rgraph render`'s"
    );
}

#[test]
fn the_presented_image_is_the_rendered_one() {
    screenshot_equals_render(&[], &[], "render.png", "render.png");
}

#[test]
fn a_debug_view_is_presented_as_rendered() {
    let edges = ["--view", "edges"];
    screenshot_equals_render(&edges, &edges, "render.png", "render.png");
}

/// The camera turned through the host's frame inputs: `view --orbit 30` shows the last
/// frame of `render --frames 2 --orbit 30`.
#[test]
fn an_orbited_camera_is_presented_as_rendered() {
    let render = ["--frames", "2", "--orbit", "30"];
    screenshot_equals_render(
        &["--orbit", "30"],
        &render,
        "frame_%04d.png",
        "frame_0001.png",
    );
}

/// The scene's first animation plays: a cube the animation holds at x = -3 for 1000 s
/// (STEP; at rest it is at the origin) is presented as `render --animation 0 --time 0`
/// draws it.
#[test]
fn the_first_animation_poses_the_presented_frames() {
    let dir = tempfile::tempdir().expect("a temporary directory");
    let cube = sliding_cube(dir.path(), "STEP", 1000.0);
    let scene = ["--scene", cube.to_str().expect("temp paths are UTF-8")];
    let posed = [&scene[..], &["--animation", "0", "--time", "0"]].concat();
    screenshot_equals_render(&scene, &posed, "render.png", "render.png");
}

/// stderr of a running viewer, line by line, kept for failure messages.
struct Lines {
    receiver: Receiver<String>,
    seen: Vec<String>,
}

impl Lines {
    fn of(stream: impl Read + Send + 'static) -> Lines {
        let (sender, receiver) = channel();
        std::thread::spawn(move || {
            for line in BufReader::new(stream).lines() {
                let Ok(line) = line else { break };
                if sender.send(line).is_err() {
                    break;
                }
            }
        });
        Lines {
            receiver,
            seen: Vec::new(),
        }
    }

    /// Waits (up to two minutes: lavapipe in a debug build on a busy machine) for a line
    /// for which `wanted` holds, and returns it.
    fn wait_for(&mut self, what: &str, wanted: impl Fn(&str) -> bool) -> String {
        let deadline = Instant::now() + Duration::from_secs(120);
        loop {
            let left = deadline.saturating_duration_since(Instant::now());
            match self.receiver.recv_timeout(left) {
                Ok(line) => {
                    self.seen.push(line.clone());
                    if wanted(&line) {
                        return line;
                    }
                }
                Err(_) => panic!(
                    "no stderr line {what} within 120 s; stderr so far:\n{}",
                    self.seen.join("\n")
                ),
            }
        }
    }
}

/// The LINE and COL of an error line that reads `FILE:LINE:COL: error: ...` with `file`.
fn located(line: &str, file: &Path) -> (u32, u32) {
    let rest = line
        .strip_prefix(&format!("{}:", file.display()))
        .unwrap_or_else(|| panic!("the error does not start with {}: {line}", file.display()));
    let mut parts = rest.splitn(3, ':');
    let mut number = || parts.next().and_then(|n| n.parse::<u32>().ok());
    let position = (number(), number());
    match (position, rest.split_once(": error: ")) {
        ((Some(l), Some(c)), Some(_)) => (l, c),
        _ => panic!("not FILE:LINE:COL: error: ...: {line}"),
    }
}

/// Replaces `path`'s contents at once (a rename), so the viewer never reads half a file.
fn edit(path: &Path, text: &str) {
    let temp = path.with_extension("partial");
    std::fs::write(&temp, text).expect("write");
    std::fs::rename(&temp, path).expect("rename");
}

const GRAPH: &str = r#"Graph(
    resources: { "color": Texture(format: "rgba8unorm-srgb") },
    passes: [
        (name: "fill", plugin: "fullscreen", params: (shader: "fill.wgsl"),
         outputs: { "color": "color" }),
    ],
    outputs: ["color"],
)
"#;

fn shader(color: &str) -> String {
    format!(
        "@fragment\nfn fs_main(@location(0) uv: vec2<f32>) -> @location(0) vec4<f32> {{\n    \
         return vec4<f32>({color});\n}}\n"
    )
}

#[test]
fn hot_reload_takes_valid_edits_and_reports_invalid_ones_while_running() {
    let x = Xvfb::start();
    let dir = tempfile::tempdir().expect("a temporary directory");
    let graph = dir.path().join("graph.ron");
    let fill = dir.path().join("fill.wgsl");
    std::fs::write(&graph, GRAPH).expect("write");
    std::fs::write(&fill, shader("1.0, 0.0, 0.0, 1.0")).expect("write");
    let graph_arg = graph.to_str().expect("temp paths are UTF-8");
    let mut child = x
        .rgraph(&[
            "view",
            "--pipeline",
            graph_arg,
            "--width",
            "64",
            "--height",
            "48",
            "--poll-ms",
            "20",
            "--frames",
            "1000000000",
        ])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("rgraph runs");
    let mut lines = Lines::of(child.stderr.take().expect("piped"));
    let window = lines.wait_for("opening the window", |l| l.starts_with("window "));
    assert!(
        window.contains("fill.wgsl"),
        "the shader is watched: {window}"
    );

    // A valid edit of the shader: reloaded.
    edit(&fill, &shader("0.0, 1.0, 0.0, 1.0"));
    lines.wait_for("reporting the shader's reload", |l| {
        l.starts_with("reloaded ") && l.contains("fill.wgsl changed")
    });

    // An invalid edit of the shader: its FILE:LINE:COL error, and the old graph runs on.
    edit(&fill, &shader("0.0, 0.0, 1.0"));
    let error = lines.wait_for("with the shader's error", |l| l.contains(": error: "));
    // The graph file's line naming the shader, then the shader's own FILE:LINE:COL.
    assert_eq!(located(&error, &graph).0, 4, "the pass's line: {error}");
    assert!(
        error.contains(&format!("{}:3:", fill.display())),
        "names the shader's return line: {error}"
    );
    lines.wait_for("saying the last good graph runs", |l| {
        l.starts_with("reload failed (") && l.contains("keeps running")
    });
    assert!(
        child.try_wait().expect("status").is_none(),
        "the viewer exited"
    );

    // An invalid edit of the graph file (the shader fixed with it, one poll later at most).
    edit(&fill, &shader("0.0, 0.0, 1.0, 1.0"));
    lines.wait_for("reloading the fixed shader", |l| l.starts_with("reloaded "));
    edit(&graph, &GRAPH.replace("\"fullscreen\"", "\"fullscren\""));
    let error = lines.wait_for("with the graph file's error", |l| l.contains(": error: "));
    assert_eq!(located(&error, &graph).0, 4, "the pass's line: {error}");
    assert!(
        error.contains("fullscren"),
        "names the unknown plugin: {error}"
    );
    lines.wait_for("saying the last good graph runs", |l| {
        l.starts_with("reload failed (")
    });
    assert!(
        child.try_wait().expect("status").is_none(),
        "the viewer exited"
    );
    // The title shows the error, with the last good graph's view and pass time.
    let located_error = format!("ERROR: {}:4:", graph.display());
    x.wait_for_title(&[
        "rgraph view: graph.ron",
        &located_error,
        "[final 1/1] orbit 0 deg: fill ",
    ]);

    // Fixed again: reloaded, still running.
    edit(&graph, GRAPH);
    lines.wait_for("reloading the fixed graph", |l| {
        l.starts_with("reloaded ") && l.contains("graph.ron changed")
    });
    assert!(
        child.try_wait().expect("status").is_none(),
        "the viewer exited"
    );
    let titles = x.wait_for_title(&["rgraph view: graph.ron [final 1/1] orbit 0 deg: fill "]);
    assert!(
        !titles.contains("ERROR"),
        "a good reload clears the error: {titles}"
    );
    child.kill().expect("kill");
    child.wait().expect("wait");
}

/// Presses keys (and drags the mouse) in the viewer's window as a user would, through the X server's XTEST
/// extension (Xvfb has it), after giving the window the keyboard focus.
struct Keyboard {
    connection: x11rb::rust_connection::RustConnection,
    root: u32,
}

impl Keyboard {
    fn on(x: &Xvfb) -> Keyboard {
        let (connection, screen) = x11rb::connect(Some(&x.display)).expect("connects to Xvfb");
        let root = connection.setup().roots[screen].root;
        Keyboard { connection, root }
    }

    /// Focuses the top-level window whose name contains "rgraph view", and returns it.
    fn focus_viewer(&self) -> u32 {
        use x11rb::protocol::xproto::{AtomEnum, ConnectionExt as _, InputFocus};
        let tree = self
            .connection
            .query_tree(self.root)
            .expect("query")
            .reply()
            .expect("tree");
        let window = tree
            .children
            .iter()
            .copied()
            .find(|&w| {
                let name = self
                    .connection
                    .get_property(false, w, AtomEnum::WM_NAME, AtomEnum::ANY, 0, 4096)
                    .expect("get_property")
                    .reply()
                    .expect("property");
                String::from_utf8_lossy(&name.value).contains("rgraph view")
            })
            .expect("the viewer's window is a child of the root");
        self.connection
            .set_input_focus(InputFocus::PARENT, window, x11rb::CURRENT_TIME)
            .expect("focus");
        self.connection.flush().expect("flush");
        window
    }

    /// Resizes `window` as a window manager would.
    fn resize(&self, window: u32, (width, height): (u32, u32)) {
        use x11rb::protocol::xproto::{ConfigureWindowAux, ConnectionExt as _};
        let size = ConfigureWindowAux::new().width(width).height(height);
        self.connection
            .configure_window(window, &size)
            .expect("configure");
        self.connection.flush().expect("flush");
    }

    /// Presses and releases the key that types `keysym`.
    fn press(&self, keysym: u32) {
        use x11rb::protocol::xproto::{ConnectionExt as _, KEY_PRESS_EVENT, KEY_RELEASE_EVENT};
        use x11rb::protocol::xtest::ConnectionExt as _;
        let setup = self.connection.setup();
        let (min, max) = (setup.min_keycode, setup.max_keycode);
        let mapping = self
            .connection
            .get_keyboard_mapping(min, max - min + 1)
            .expect("mapping")
            .reply()
            .expect("mapping reply");
        let per = usize::from(mapping.keysyms_per_keycode);
        let index = mapping
            .keysyms
            .chunks(per)
            .position(|syms| syms.contains(&keysym))
            .unwrap_or_else(|| panic!("no key types keysym {keysym:#x}"));
        let keycode = min + u8::try_from(index).expect("keycodes are bytes");
        for event in [KEY_PRESS_EVENT, KEY_RELEASE_EVENT] {
            self.connection
                .xtest_fake_input(event, keycode, x11rb::CURRENT_TIME, self.root, 0, 0, 0)
                .expect("fake input");
        }
        self.connection.flush().expect("flush");
    }
}

impl Keyboard {
    /// Drags with the left mouse button held from `from` to `to`, in root (here: window)
    /// coordinates.
    fn drag(&self, from: (i16, i16), to: (i16, i16)) {
        use x11rb::protocol::xproto::{
            BUTTON_PRESS_EVENT, BUTTON_RELEASE_EVENT, MOTION_NOTIFY_EVENT,
        };
        use x11rb::protocol::xtest::ConnectionExt as _;
        let fake = |event: u8, detail: u8, (x, y): (i16, i16)| {
            self.connection
                .xtest_fake_input(event, detail, x11rb::CURRENT_TIME, self.root, x, y, 0)
                .expect("fake input");
        };
        // One event at a time, each given time to arrive before the next.
        for (event, detail, at) in [
            (MOTION_NOTIFY_EVENT, 0, from),
            (BUTTON_PRESS_EVENT, 1, from),
            (MOTION_NOTIFY_EVENT, 0, to),
            (BUTTON_RELEASE_EVENT, 1, to),
        ] {
            fake(event, detail, at);
            self.connection.flush().expect("flush");
            std::thread::sleep(Duration::from_millis(300));
        }
    }
}

/// X keysyms of the keys pressed.
const KEY_V: u32 = 0x76;
const KEY_RIGHT: u32 = 0xff53;

#[test]
fn keys_pick_the_view_keys_and_drags_orbit_the_camera_and_a_resize_recompiles() {
    let x = Xvfb::start();
    let mut child = x
        .rgraph(&[
            "view",
            "--pipeline",
            "pipelines/deferred_msaa_4x_tiled.ron",
            "--width",
            "160",
            "--height",
            "96",
            "--frames",
            "1000000000",
        ])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("rgraph runs");
    let mut lines = Lines::of(child.stderr.take().expect("piped"));
    lines.wait_for("opening the window", |l| l.starts_with("window "));
    x.wait_for_title(&["[final 1/", "orbit 0 deg: "]);
    let keyboard = Keyboard::on(&x);
    let window = keyboard.focus_viewer();

    // V: the next view, "color" being the first, the debug views after it by name.
    keyboard.press(KEY_V);
    let picked = lines.wait_for("showing the next view", |l| l.starts_with("reloaded "));
    assert!(
        picked.contains("(view picked)") && picked.contains(": showing debug.albedo (2/"),
        "{picked}"
    );
    x.wait_for_title(&["[albedo 2/", "gbuffer "]);

    // Right arrow, six times: 5 degrees each.
    for _ in 0..6 {
        keyboard.press(KEY_RIGHT);
    }
    x.wait_for_title(&["[albedo 2/", "orbit 30 deg: "]);

    // Dragging 75 pixels left turns it back: 0.4 degrees a pixel.
    keyboard.drag((100, 50), (25, 50));
    x.wait_for_title(&["[albedo 2/", "orbit 0 deg: "]);

    // A new window size: the graph is compiled again at that size.
    keyboard.resize(window, (120, 80));
    let resized = lines.wait_for("reloading at the new size", |l| l.starts_with("reloaded "));
    assert!(resized.contains("(the window is 120x80)"), "{resized}");
    assert!(
        child.try_wait().expect("status").is_none(),
        "the viewer exited"
    );
    child.kill().expect("kill");
    child.wait().expect("wait");
}

#[test]
fn without_a_display_it_says_which_variables_it_needs() {
    let dir = tempfile::tempdir().expect("a temporary directory");
    let out = Command::new(env!("CARGO_BIN_EXE_rgraph"))
        .args(["view", "--frames", "1"])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .env_remove("WAYLAND_SOCKET")
        .env("XDG_RUNTIME_DIR", dir.path())
        .output()
        .expect("rgraph runs");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("needs a display")
            && stderr.contains("DISPLAY")
            && stderr.contains("WAYLAND_DISPLAY"),
        "{stderr}"
    );
    // winit's reason without the source file it was raised in (a path in the build
    // machine's cargo registry).
    assert!(stderr.contains("error: cannot open a window: "), "{stderr}");
    assert!(
        !stderr.contains(".rs:") && !stderr.contains("registry"),
        "{stderr}"
    );
}
