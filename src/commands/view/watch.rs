//! The files a graph is built from, polled for changes: the graph file, the graph files it
//! builds on (a preset's `base`) and the WGSL files they name.
//!
//! Which files those are is read from the graph files' text: every string literal ending
//! in `.ron` or `.wgsl`, resolved from the folder of the file that names it, as the loader
//! resolves them. A literal that names no file (a comment's example, say) is watched too,
//! harmlessly: it only ever changes by appearing. The deferred plugins' own shaders are
//! compiled into the binary and are not watched.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::time::SystemTime;

use rgraph_core::bounded_read;

/// What a watched file looked like when last polled: `None` when it could not be read
/// (missing, or built in), else its modification time and length.
type Stamp = Option<(SystemTime, u64)>;

/// The watched files and their stamps at the last poll.
pub struct Watch {
    files: BTreeMap<PathBuf, Stamp>,
}

impl Watch {
    /// Watches `graph` and every file it names, recursively through named graph files,
    /// stamped as they are now.
    pub fn new(graph: &Path) -> Watch {
        let mut files = BTreeMap::new();
        let mut pending = vec![graph.to_path_buf()];
        while let Some(path) = pending.pop() {
            if files.contains_key(&path) {
                continue;
            }
            files.insert(path.clone(), stamp(&path));
            if path.extension().is_some_and(|e| e == "ron") {
                pending.extend(named_files(&path));
            }
        }
        Watch { files }
    }

    /// The watched files, sorted.
    pub fn files(&self) -> impl Iterator<Item = &Path> {
        self.files.keys().map(PathBuf::as_path)
    }

    /// The first watched file whose stamp differs from the last poll's, if any; every
    /// stamp is brought up to date, so a change is reported once.
    pub fn changed(&mut self) -> Option<PathBuf> {
        let mut first = None;
        for (path, old) in &mut self.files {
            let now = stamp(path);
            if now != *old {
                *old = now;
                first.get_or_insert_with(|| path.clone());
            }
        }
        first
    }
}

fn stamp(path: &Path) -> Stamp {
    let meta = std::fs::metadata(path).ok()?;
    Some((meta.modified().ok()?, meta.len()))
}

/// The `.ron` and `.wgsl` files `graph`'s text names, resolved from its folder; none when
/// it cannot be read (it is watched itself, so fixing it is noticed).
fn named_files(graph: &Path) -> Vec<PathBuf> {
    let Ok(text) = bounded_read::read_text(graph, bounded_read::MAX_GRAPH_FILE_BYTES) else {
        return Vec::new();
    };
    let dir = graph.parent().unwrap_or(Path::new(""));
    string_literals(&text)
        .filter(|s| s.ends_with(".ron") || s.ends_with(".wgsl"))
        .map(|s| dir.join(s))
        .collect()
}

/// The contents of the double-quoted string literals of RON text, without escapes (file
/// names have none).
fn string_literals(text: &str) -> impl Iterator<Item = &str> {
    text.split('"').skip(1).step_by(2)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn literals_are_the_quoted_parts() {
        let text = r#"(shader: "../shaders/a.wgsl", base: "b.ron", name: "x")"#;
        let found: Vec<&str> = string_literals(text).collect();
        assert_eq!(found, ["../shaders/a.wgsl", "b.ron", "x"]);
    }

    #[test]
    fn watches_named_files_through_presets_and_reports_a_change_once() {
        let dir = tempfile::tempdir().expect("a temporary directory");
        let base = dir.path().join("base.ron");
        let preset = dir.path().join("preset.ron");
        let shader = dir.path().join("sub").join("s.wgsl");
        std::fs::create_dir(dir.path().join("sub")).expect("mkdir");
        std::fs::write(
            &base,
            r#"Graph(passes: [(params: (shader: "sub/s.wgsl"))])"#,
        )
        .expect("write");
        std::fs::write(&preset, r#"Preset(base: "base.ron")"#).expect("write");
        std::fs::write(&shader, "// shader").expect("write");
        let mut watch = Watch::new(&preset);
        let files: Vec<&Path> = watch.files().collect();
        assert_eq!(files, [base.as_path(), preset.as_path(), shader.as_path()]);
        assert_eq!(watch.changed(), None);
        std::fs::write(&shader, "// shader, edited").expect("write");
        assert_eq!(watch.changed(), Some(shader));
        assert_eq!(watch.changed(), None);
    }
}
