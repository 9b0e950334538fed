//! The files a graph file names (a preset's `base`, a pass's `shader`): resolved from the
//! folder of the file that names them, kept inside the folders graph files may reach (see
//! [`Registry`](super::Registry)), and read. A reference that leaves them is refused before anything is
//! read, so no error can quote a file outside them.

use std::path::{Component, Path, PathBuf};

use crate::bounded_read::{self, ReadError};
use crate::embedded;
use crate::folders::Folders;

/// Where a graph's references may lead.
pub(crate) struct References {
    /// `None` for passes declared in code ([`add_plugin_pass`]), whose paths are the
    /// program's own: any file, relative to the current directory.
    ///
    /// [`add_plugin_pass`]: crate::GraphBuilder::add_plugin_pass
    folders: Option<Folders>,
}

/// A file a reference named, read.
pub(crate) struct Named {
    /// The path for messages: the referring file's folder as given, joined with the
    /// reference, `..` folded away where it can be.
    pub path: PathBuf,
    pub text: String,
}

/// Why a reference could not be read.
#[derive(Debug)]
pub(crate) enum ReferenceError {
    /// The reference itself is refused: why, as the end of a sentence about it.
    Refused(String),
    /// The file it names cannot be read; `path` as in [`Named::path`].
    Unreadable { path: PathBuf, reason: ReadError },
}

impl References {
    /// The references of the graph file at `file` (as given; the file itself need not be on
    /// disk): its folder, the built-in files' folders, a registry's graph `roots` and
    /// `extra`.
    pub fn of_file(file: &Path, roots: &Folders, extra: &Folders) -> Self {
        let mut folders = Folders::new();
        folders.allow_virtual(folder_of(file));
        for shipped in embedded::folders() {
            folders.allow_virtual(Path::new(shipped));
        }
        folders.extend(roots);
        folders.extend(extra);
        References {
            folders: Some(folders),
        }
    }

    /// Passes declared in code: any path.
    pub fn unrestricted() -> Self {
        References { folders: None }
    }

    /// Reads the file `reference` names, written in a file in the folder `dir` (as given),
    /// of at most `max_bytes`. A relative path missing from disk is read from the built-in
    /// files (see [`embedded`]).
    pub fn read(
        &self,
        dir: &Path,
        reference: &str,
        max_bytes: u64,
    ) -> Result<Named, ReferenceError> {
        check_text(reference)?;
        let path = shown(dir, reference);
        let unreadable = |reason| ReferenceError::Unreadable {
            path: path.clone(),
            reason,
        };
        let Some(folders) = &self.folders else {
            let text = embedded::read_text(&path, max_bytes).map_err(unreadable)?;
            return Ok(Named { path, text });
        };
        if Path::new(reference).has_root() {
            return Err(ReferenceError::Refused(
                "is an absolute path; a graph file names files relative to its own folder"
                    .to_owned(),
            ));
        }
        let inside = folders
            .resolve(dir, Path::new(reference))
            .map_err(|outside| {
                ReferenceError::Refused(format!(
                    "{outside}, outside the folders graph files may read ({folders}); another \
                 is allowed with --graph-root DIR"
                ))
            })?;
        let text = match inside.real {
            Ok(real) => bounded_read::read_text(&real, max_bytes).map_err(unreadable)?,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => embedded::get(&inside.lexical)
                .map(str::to_owned)
                .ok_or_else(|| unreadable(ReadError::Io(e)))?,
            Err(e) => return Err(unreadable(ReadError::Io(e))),
        };
        Ok(Named { path, text })
    }
}

/// Refuses references that name no file: empty, or with a control character (no file
/// name a graph file means has one, and a NUL cannot reach the OS).
fn check_text(reference: &str) -> Result<(), ReferenceError> {
    if reference.trim().is_empty() {
        return Err(ReferenceError::Refused("is empty: name a file".to_owned()));
    }
    match reference.chars().find(|c| c.is_control()) {
        Some(c) => Err(ReferenceError::Refused(format!(
            "contains the control character {}, which no file name a graph file names has",
            c.escape_unicode()
        ))),
        None => Ok(()),
    }
}

/// The folder of the file `file`: `.` for a bare file name.
fn folder_of(file: &Path) -> &Path {
    match file.parent() {
        Some(parent) if !parent.as_os_str().is_empty() => parent,
        _ => Path::new("."),
    }
}

/// `reference` joined to the folder `dir`, with `..` folded away where it follows a
/// folder name, so messages show short paths.
fn shown(dir: &Path, reference: &str) -> PathBuf {
    let mut path = PathBuf::new();
    for component in dir.join(reference).components() {
        match component {
            Component::CurDir => {}
            Component::ParentDir
                if matches!(path.components().next_back(), Some(Component::Normal(_))) =>
            {
                path.pop();
            }
            other => path.push(other),
        }
    }
    path
}

#[cfg(test)]
mod tests {
    use super::shown;
    use crate::file::shown::Shown;
    use std::path::Path;

    #[test]
    fn shown_paths_fold_dots_and_escape_control_characters() {
        assert_eq!(
            shown(Path::new("pipelines"), "../shaders/a.wgsl"),
            Path::new("shaders/a.wgsl")
        );
        assert_eq!(shown(Path::new(""), "../a.wgsl"), Path::new("../a.wgsl"));
        assert_eq!(Shown("a\0b\n").to_string(), "\"a\\0b\\n\"");
    }
}
