//! Files built into a program, read when they are missing from disk.
//!
//! A program that ships graph files and shaders (the `rgraph` binary embeds `pipelines/`,
//! `shaders/` and `bench/graphs/`) provides them once with [`provide`]; graph files and
//! shaders named by a relative path that does not exist on disk are then read from there,
//! so the program works from any directory while files on disk still override. A path
//! matches after `.` and `..` are applied to its text: `pipelines/../shaders/a.wgsl` is
//! `shaders/a.wgsl`. The built-in files lie, as it were, in the current directory: an
//! absolute path matches where it lies under it (so a file named by a path typed either
//! way finds the same built-in file), and paths that climb above it never match.

use std::path::{Component, Path};
use std::sync::OnceLock;

use crate::bounded_read::{self, ReadError};

/// `(path relative to the program's source root, with '/' separators, contents)`.
pub type EmbeddedFile = (&'static str, &'static str);

static FILES: OnceLock<&'static [EmbeddedFile]> = OnceLock::new();

/// Makes `files` the built-in files, for the whole process. Only the first call counts: a
/// program has one set.
pub fn provide(files: &'static [EmbeddedFile]) {
    let _ = FILES.set(files);
}

/// The built-in file `path` names, if any.
pub fn get(path: &Path) -> Option<&'static str> {
    let key = normalise(path)?;
    FILES
        .get()?
        .iter()
        .find(|(name, _)| *name == key)
        .map(|(_, text)| *text)
}

/// The built-in files directly in directory `dir` (e.g. `"pipelines"`), by path.
pub fn list(dir: &str) -> Vec<&'static str> {
    let files = FILES.get().map_or(&[][..], |f| *f);
    files
        .iter()
        .map(|(name, _)| *name)
        .filter(|name| {
            name.strip_prefix(dir)
                .and_then(|rest| rest.strip_prefix('/'))
                .is_some_and(|file| !file.contains('/'))
        })
        .collect()
}

/// The folders the built-in files are in (`pipelines`, `shaders`, ...), sorted: graph files
/// may name the files of these shipped trees (see [`file`](crate::file)).
pub fn folders() -> Vec<&'static str> {
    let files = FILES.get().map_or(&[][..], |f| *f);
    let mut folders: Vec<&str> = files
        .iter()
        .filter_map(|(name, _)| name.rsplit_once('/').map(|(dir, _)| dir))
        .collect();
    folders.sort_unstable();
    folders.dedup();
    folders
}

/// Whether `path` is a file on disk or, missing there, a built-in one.
pub fn exists(path: &Path) -> bool {
    path.is_file() || (!path.exists() && get(path).is_some())
}

/// [`bounded_read::read_text`], falling back to the built-in file when `path` does not
/// exist on disk.
pub fn read_text(path: &Path, max_bytes: u64) -> Result<String, ReadError> {
    match bounded_read::read_text(path, max_bytes) {
        Err(ReadError::Io(e)) if e.kind() == std::io::ErrorKind::NotFound => {
            get(path).map(str::to_owned).ok_or(ReadError::Io(e))
        }
        other => other,
    }
}

/// `path` as an embedded file's key, or `None` when it lies outside the current directory.
fn normalise(path: &Path) -> Option<String> {
    let cwd = std::env::current_dir().ok();
    let relative = match cwd.as_deref().and_then(|cwd| path.strip_prefix(cwd).ok()) {
        Some(inside) => inside,
        None => path,
    };
    let mut parts: Vec<&str> = Vec::new();
    for component in relative.components() {
        match component {
            Component::CurDir => {}
            Component::ParentDir => {
                parts.pop()?;
            }
            Component::Normal(part) => parts.push(part.to_str()?),
            Component::RootDir | Component::Prefix(_) => return None,
        }
    }
    Some(parts.join("/"))
}

#[cfg(test)]
mod tests {
    use super::normalise;
    use std::path::Path;

    #[test]
    fn paths_match_after_dots_and_never_when_outside_the_current_directory() {
        let key = |p: &str| normalise(Path::new(p));
        let cwd = std::env::current_dir().unwrap();
        assert_eq!(
            normalise(&cwd.join("pipelines/a.ron")).as_deref(),
            Some("pipelines/a.ron")
        );
        assert_eq!(key("pipelines/a.ron").as_deref(), Some("pipelines/a.ron"));
        assert_eq!(
            key("./pipelines/../shaders/a.wgsl").as_deref(),
            Some("shaders/a.wgsl")
        );
        assert_eq!(key("/pipelines/a.ron"), None);
        assert_eq!(key("../pipelines/a.ron"), None);
    }
}
