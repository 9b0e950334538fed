//! The built `rgraph` binary run as a user runs it, from the repository root (or another
//! directory), for the command-line tests: exit status, stdout and stderr.

use std::path::Path;
use std::process::Command;

pub struct Run {
    /// A signal (a crash) has no code: -1, which never matches an expected status.
    pub code: i32,
    pub stdout: String,
    pub stderr: String,
}

/// Runs `rgraph` with `args`.
pub fn rgraph(args: &[&str]) -> Run {
    rgraph_in(Path::new(env!("CARGO_MANIFEST_DIR")), args)
}

/// Runs `rgraph` with `args` in directory `dir`.
pub fn rgraph_in(dir: &Path, args: &[&str]) -> Run {
    let output = Command::new(env!("CARGO_BIN_EXE_rgraph"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("the rgraph binary runs");
    Run {
        code: output.status.code().unwrap_or(-1),
        stdout: String::from_utf8_lossy(&output.stdout).into_owned(),
        stderr: String::from_utf8_lossy(&output.stderr).into_owned(),
    }
}

impl Run {
    /// Fails with everything the binary said when it did not exit with `code`.
    pub fn expect(self, code: i32) -> Self {
        assert_eq!(
            self.code, code,
            "expected exit {code}\nstdout:\n{}\nstderr:\n{}",
            self.stdout, self.stderr
        );
        self
    }

    pub fn stderr_has(&self, text: &str) -> &Self {
        assert!(
            self.stderr.contains(text),
            "expected stderr to contain {text:?}, got:\n{}",
            self.stderr
        );
        self
    }
}

/// A forward MSAA graph file of the opaque scene alone: no pass draws alpha BLEND
/// materials, points or lines, for the tests of `rgraph render`'s warnings that a
/// pipeline leaves part of a scene out.
pub const FORWARD_OPAQUE_ONLY: &str = r#"Graph(
    resources: {
        "hdr": Texture(format: "rgba16float", samples: 4),
        "depth": Texture(format: "depth24plus-stencil8", samples: 4),
        "resolved": Texture(format: "rgba16float"),
        "color": Texture(format: "rgba8unorm-srgb"),
    },
    passes: [
        (name: "forward", plugin: "forward", outputs: { "hdr": "hdr", "depth": "depth" }),
        (name: "resolve", plugin: "resolve", inputs: { "hdr": "hdr" },
         outputs: { "resolved": "resolved" }),
        (name: "tonemap", plugin: "tonemap", inputs: { "hdr": "resolved" },
         outputs: { "color": "color" }),
    ],
    outputs: ["color"],
)"#;

/// What `rgraph render` of `scene` through `pipeline` at `size` says on stderr, the
/// frame written to `out`; fails unless it succeeds.
pub fn render_stderr(
    pipeline: &str,
    scene: &str,
    (width, height): (u32, u32),
    out: &Path,
) -> String {
    let (width, height) = (width.to_string(), height.to_string());
    rgraph(&[
        "render",
        "--pipeline",
        pipeline,
        "--scene",
        scene,
        "--width",
        &width,
        "--height",
        &height,
        "--out",
        out.to_str().expect("temp paths are UTF-8"),
    ])
    .expect(0)
    .stderr
}
