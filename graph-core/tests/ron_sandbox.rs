//! Graph files reach only their own folder, the built-in files' folders and the folders a
//! registry allows (`Registry::allow_graph_root`): a preset's base or a shader anywhere else
//! (an absolute path, a `..` that climbs out, a link that leads out) is refused naming the
//! file, the line and column of the reference and the reference, and is never read, so no
//! error can quote it. Empty references and control characters are refused, escaped.

use std::path::{Path, PathBuf};

use rgraph_core::file::{load_file, load_str, validate_file, FileErrors, Registry};
use rgraph_core::CompileOptions;

/// What the planted files outside the graph's folder hold: no error may show it.
const SECRET: &str = "SECRET-7f3a";

/// `graphs/`, the folder graph files are loaded from, and `outside/` beside it holding
/// `secret.ron` and `secret.wgsl`, with links to both from inside `graphs/`.
struct Planted {
    _dir: tempfile::TempDir,
    graphs: PathBuf,
    outside: PathBuf,
}

fn planted() -> Planted {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let graphs = dir.path().join("graphs");
    let outside = dir.path().join("outside");
    std::fs::create_dir_all(&graphs).unwrap();
    std::fs::create_dir_all(&outside).unwrap();
    for name in ["secret.ron", "secret.wgsl"] {
        std::fs::write(outside.join(name), format!("{SECRET} (\n")).unwrap();
    }
    #[cfg(unix)]
    for name in ["secret.ron", "secret.wgsl"] {
        std::os::unix::fs::symlink(outside.join(name), graphs.join(format!("link_{name}")))
            .unwrap();
    }
    Planted {
        _dir: dir,
        graphs,
        outside,
    }
}

fn preset(base: &str) -> String {
    format!("Preset(base: \"{base}\")")
}

/// A full-screen pass drawing `shader` into "c"; the shader's string starts at 3:67.
fn graph(shader: &str) -> String {
    format!(
        "Graph(\n    resources: {{ \"c\": Texture(format: \"rgba8unorm\") }},\n    passes: [(name: \"sky\", plugin: \"fullscreen\", params: (shader: \"{shader}\"), outputs: {{ \"color\": \"c\" }})],\n    outputs: [\"c\"],\n)"
    )
}

fn refused(path: &Path, text: &str, registry: &Registry) -> String {
    let errors: FileErrors = load_str(path, text, registry)
        .map(drop)
        .expect_err("the reference is refused");
    let message = errors.to_string();
    assert!(
        !message.contains(SECRET),
        "the error quotes the file: {message}"
    );
    assert_eq!(errors.0.len(), 1, "{message}");
    message
}

/// The sentence a refusal of a reference outside `graphs` ends with.
fn outside_of(graphs: &Path, how: String) -> String {
    format!(
        "{how}, outside the folders graph files may read ({}); another is allowed with \
         --graph-root DIR",
        graphs.display()
    )
}

#[test]
fn a_preset_s_base_outside_the_folder_is_refused_without_reading_it() {
    let p = planted();
    let file = p.graphs.join("p.ron");
    let real = p.outside.canonicalize().unwrap().join("secret.ron");
    let absolute = p.outside.join("secret.ron").display().to_string();
    let mut cases = vec![
        (
            absolute,
            "is an absolute path; a graph file names files relative to its own folder".to_owned(),
        ),
        (
            "../outside/secret.ron".to_owned(),
            outside_of(
                &p.graphs,
                format!("points to {}", p.outside.join("secret.ron").display()),
            ),
        ),
        (
            "sub/../../../outside/secret.ron".to_owned(),
            outside_of(
                &p.graphs,
                format!(
                    "points to {}",
                    p.outside
                        .parent()
                        .unwrap()
                        .parent()
                        .unwrap()
                        .join("outside/secret.ron")
                        .display()
                ),
            ),
        ),
    ];
    if cfg!(unix) {
        cases.push((
            "link_secret.ron".to_owned(),
            outside_of(
                &p.graphs,
                format!("leads (through a symbolic link) to {}", real.display()),
            ),
        ));
    }
    for (base, why) in cases {
        let message = refused(&file, &preset(&base), &Registry::with_builtins());
        assert_eq!(
            message,
            format!(
                "{}:1:14: error: the preset's base \"{base}\" {why}",
                file.display()
            )
        );
    }
}

#[test]
fn a_shader_outside_the_folder_is_refused_without_reading_it() {
    let p = planted();
    let file = p.graphs.join("g.ron");
    let mut cases = vec![
        (
            p.outside.join("secret.wgsl").display().to_string(),
            "is an absolute path; a graph file names files relative to its own folder".to_owned(),
        ),
        (
            "../outside/secret.wgsl".to_owned(),
            outside_of(
                &p.graphs,
                format!("points to {}", p.outside.join("secret.wgsl").display()),
            ),
        ),
    ];
    if cfg!(unix) {
        let real = p.outside.canonicalize().unwrap().join("secret.wgsl");
        cases.push((
            "link_secret.wgsl".to_owned(),
            outside_of(
                &p.graphs,
                format!("leads (through a symbolic link) to {}", real.display()),
            ),
        ));
    }
    for (shader, why) in cases {
        let message = refused(&file, &graph(&shader), &Registry::with_builtins());
        assert_eq!(
            message,
            format!(
                "{}:3:67: error: pass \"sky\" (fullscreen): shader \"{shader}\" {why}",
                file.display()
            )
        );
    }
}

#[test]
fn empty_references_and_control_characters_are_refused_escaped() {
    let p = planted();
    let file = p.graphs.join("p.ron");
    let registry = Registry::with_builtins();
    assert_eq!(
        refused(&file, &preset(""), &registry),
        format!(
            "{}:1:14: error: the preset's base \"\" is empty: name a file",
            file.display()
        )
    );
    // RON's `\u{0}` escape: the name holds a NUL, which the message shows escaped.
    assert_eq!(
        refused(&file, &preset("a\\u{0}b.ron"), &registry),
        format!(
            "{}:1:1: error: the preset's base \"a\\0b.ron\" contains the control character \
             \\u{{0}}, which no file name a graph file names has",
            file.display()
        )
    );
    let shader = refused(&file, &graph("a\\nb.wgsl"), &registry);
    assert!(
        shader.ends_with(
            "pass \"sky\" (fullscreen): shader \"a\\nb.wgsl\" contains the control character \
             \\u{a}, which no file name a graph file names has"
        ),
        "{shader}"
    );
}

#[test]
fn a_registry_s_graph_roots_open_more_folders() {
    let p = planted();
    let shared = p.outside.join("shared");
    std::fs::create_dir_all(&shared).unwrap();
    let wgsl = "@fragment fn fs_main() -> @location(0) vec4<f32> { return vec4<f32>(1.0); }";
    std::fs::write(shared.join("sky.wgsl"), wgsl).unwrap();
    let file = p.graphs.join("g.ron");
    std::fs::write(&file, graph("../outside/shared/sky.wgsl")).unwrap();
    let closed = Registry::with_builtins();
    let error = validate_file(&file, &closed, &CompileOptions::default()).unwrap_err();
    assert!(error.to_string().contains("outside the folders"), "{error}");

    let mut open = Registry::with_builtins();
    open.allow_graph_root(&shared).unwrap();
    validate_file(&file, &open, &CompileOptions::default()).unwrap_or_else(|e| panic!("{e}"));
    // Only that folder: its parent stays closed.
    let error = load_str(&file, &graph("../outside/secret.wgsl"), &open)
        .map(drop)
        .unwrap_err();
    assert!(!error.to_string().contains(SECRET), "{error}");

    let Err(error) = open.allow_graph_root(shared.join("sky.wgsl")) else {
        panic!("a file is not a folder");
    };
    assert_eq!(error.to_string(), "not a folder (it is a file)");
    assert!(open.allow_graph_root(p.outside.join("missing")).is_err());
}

#[test]
fn a_link_inside_the_folder_to_a_file_inside_it_is_followed() {
    let p = planted();
    let wgsl = "@fragment fn fs_main() -> @location(0) vec4<f32> { return vec4<f32>(1.0); }";
    std::fs::write(p.graphs.join("sky.wgsl"), wgsl).unwrap();
    #[cfg(unix)]
    std::os::unix::fs::symlink(p.graphs.join("sky.wgsl"), p.graphs.join("alias.wgsl")).unwrap();
    let file = p.graphs.join("g.ron");
    let shader = if cfg!(unix) { "alias.wgsl" } else { "sky.wgsl" };
    std::fs::write(&file, graph(shader)).unwrap();
    load_file(&file, &Registry::with_builtins()).unwrap_or_else(|e| panic!("{e}"));
}
