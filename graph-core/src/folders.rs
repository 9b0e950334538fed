//! The folders a user's file may name other files in, and the check that a named file stays
//! inside them. Graph files' references (a preset's base, a pass's shader) and glTF URIs
//! both go through it, so a hostile file can neither make the tool read a file elsewhere on
//! the machine nor have an error quote one.
//!
//! A path is inside when, with `.` and `..` applied to its text, it lies under one of the
//! folders, and when the file it reaches on disk (symbolic links resolved) lies under one
//! of them too. Both tests run before anything is read; the caller then reads
//! [`Inside::real`], the resolved file, so a link cannot be swapped in between the two.

use std::fmt;
use std::io;
use std::path::{Component, Path, PathBuf};

/// Folders, each known by its absolute path and (when it exists) its real one.
#[derive(Clone, Debug, Default)]
pub struct Folders {
    folders: Vec<Folder>,
}

#[derive(Clone, Debug, PartialEq, Eq)]
struct Folder {
    /// Absolute, with `.` and `..` applied to the text: what paths are first compared with.
    lexical: PathBuf,
    /// Symbolic links resolved; `None` for a folder that is not on disk (the built-in files'
    /// folders, when the program runs elsewhere), which no file on disk is inside.
    real: Option<PathBuf>,
}

/// A path inside the folders.
#[derive(Debug)]
pub struct Inside {
    /// Absolute, with `.` and `..` applied to the text.
    pub lexical: PathBuf,
    /// The file on disk, symbolic links resolved: what to read. An error when nothing is
    /// there (`NotFound`) or the path cannot be resolved.
    pub real: io::Result<PathBuf>,
}

/// Why a path is not inside the folders. Displayed as the end of a sentence whose subject
/// is the reference: "`../x` points to /tmp/x".
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum Outside {
    /// With `..` applied, the path lies outside every folder (an absolute path elsewhere,
    /// or one that climbs out).
    #[error("points to {}", path.display())]
    Leaves {
        /// Where it points, `..` applied.
        path: PathBuf,
    },
    /// The path lies inside, but a symbolic link on the way leads out.
    #[error("leads (through a symbolic link) to {}", path.display())]
    Link {
        /// Where the link leads.
        path: PathBuf,
    },
}

impl Folders {
    /// No folders: nothing is inside.
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds the folder `dir`, which must exist. Fails, saying why, when it cannot be
    /// resolved or is not a folder.
    pub fn allow(&mut self, dir: &Path) -> io::Result<()> {
        let real = dir.canonicalize()?;
        if !real.is_dir() {
            return Err(io::Error::new(
                io::ErrorKind::NotADirectory,
                "not a folder (it is a file)",
            ));
        }
        self.push(Folder {
            lexical: absolute(dir)?,
            real: Some(real),
        });
        Ok(())
    }

    /// Adds the folder `dir` whether or not it is on disk: a folder of built-in files, or
    /// the folder of a file given as text. Files on disk are inside it only where it exists.
    pub fn allow_virtual(&mut self, dir: &Path) {
        let real = dir.canonicalize().ok().filter(|real| real.is_dir());
        // `absolute` fails only without a current directory, where nothing relative can
        // be read either.
        if let Ok(lexical) = absolute(dir) {
            self.push(Folder { lexical, real });
        }
    }

    /// Adds every folder of `other`.
    pub fn extend(&mut self, other: &Folders) {
        for folder in &other.folders {
            self.push(folder.clone());
        }
    }

    fn push(&mut self, folder: Folder) {
        if !self.folders.contains(&folder) {
            self.folders.push(folder);
        }
    }

    /// Where `reference` (relative to the folder `from`, or absolute) leads, when that is
    /// inside the folders. Touches the file system only to resolve links; reads nothing.
    pub fn resolve(&self, from: &Path, reference: &Path) -> Result<Inside, Outside> {
        let lexical = normalise(&absolute(from).unwrap_or_default().join(reference));
        // First without the file system, so a path that leaves is refused with the same
        // message whether or not its target exists.
        let lexically_inside = self.folders.iter().any(|f| {
            lexical.starts_with(&f.lexical)
                || f.real.as_ref().is_some_and(|r| lexical.starts_with(r))
        });
        if !lexically_inside {
            return Err(Outside::Leaves { path: lexical });
        }
        // Then where it really is: a symbolic link inside a folder may lead out of it.
        let real = lexical.canonicalize();
        if let Ok(real) = &real {
            let really_inside = self
                .folders
                .iter()
                .filter_map(|f| f.real.as_ref())
                .any(|folder| real.starts_with(folder));
            if !really_inside {
                return Err(Outside::Link { path: real.clone() });
            }
        }
        Ok(Inside { lexical, real })
    }
}

/// The folders, as `A, B or C`, for messages.
impl fmt::Display for Folders {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let names: Vec<String> = self
            .folders
            .iter()
            .map(|folder| folder.lexical.display().to_string())
            .collect();
        match names.split_last() {
            None => f.write_str("no folder"),
            Some((last, [])) => f.write_str(last),
            Some((last, rest)) => write!(f, "{} or {last}", rest.join(", ")),
        }
    }
}

/// `path` made absolute against the current directory, with `.` and `..` applied to its
/// text; an empty path is the current directory.
pub fn absolute(path: &Path) -> io::Result<PathBuf> {
    let path = match path.as_os_str().is_empty() {
        true => Path::new("."),
        false => path,
    };
    Ok(normalise(&std::path::absolute(path)?))
}

/// `path` with `.` and `..` applied to its text (`..` at the root stays at the root, as
/// the OS does).
fn normalise(path: &Path) -> PathBuf {
    let mut out = PathBuf::new();
    for component in path.components() {
        match component {
            Component::CurDir => {}
            Component::ParentDir => {
                out.pop();
            }
            other => out.push(other),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::{Folders, Outside};
    use std::path::Path;

    #[test]
    fn paths_inside_resolve_and_paths_that_climb_out_are_refused() {
        let dir = tempfile::tempdir().unwrap();
        let inner = dir.path().join("inner");
        std::fs::create_dir(&inner).unwrap();
        std::fs::write(inner.join("a.txt"), "a").unwrap();
        std::fs::write(dir.path().join("secret.txt"), "s").unwrap();
        let mut folders = Folders::new();
        folders.allow(&inner).unwrap();

        let inside = folders.resolve(&inner, Path::new("./x/../a.txt")).unwrap();
        assert_eq!(
            inside.real.unwrap(),
            inner.canonicalize().unwrap().join("a.txt")
        );
        let missing = folders.resolve(&inner, Path::new("none.txt")).unwrap();
        assert_eq!(
            missing.real.unwrap_err().kind(),
            std::io::ErrorKind::NotFound
        );

        let leaves = folders
            .resolve(&inner, Path::new("../secret.txt"))
            .unwrap_err();
        assert!(matches!(&leaves, Outside::Leaves { path } if path.ends_with("secret.txt")));
        assert!(leaves.to_string().starts_with("points to /"), "{leaves}");
        let absolute = folders
            .resolve(&inner, Path::new("/etc/passwd"))
            .unwrap_err();
        assert_eq!(absolute.to_string(), "points to /etc/passwd");
    }

    #[cfg(unix)]
    #[test]
    fn a_link_that_leads_out_is_refused_and_one_that_stays_in_is_followed() {
        let dir = tempfile::tempdir().unwrap();
        let inner = dir.path().join("inner");
        std::fs::create_dir(&inner).unwrap();
        std::fs::write(dir.path().join("secret.txt"), "s").unwrap();
        std::fs::write(inner.join("a.txt"), "a").unwrap();
        std::os::unix::fs::symlink(dir.path().join("secret.txt"), inner.join("out")).unwrap();
        std::os::unix::fs::symlink(inner.join("a.txt"), inner.join("in")).unwrap();
        let mut folders = Folders::new();
        folders.allow(&inner).unwrap();

        let out = folders.resolve(&inner, Path::new("out")).unwrap_err();
        assert!(matches!(&out, Outside::Link { path } if path.ends_with("secret.txt")));
        let followed = folders.resolve(&inner, Path::new("in")).unwrap();
        assert!(followed.real.unwrap().ends_with("inner/a.txt"));
    }

    #[test]
    fn only_folders_are_allowed_and_virtual_ones_hold_no_file_on_disk() {
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("f.txt");
        std::fs::write(&file, "f").unwrap();
        let mut folders = Folders::new();
        let error = folders.allow(&file).unwrap_err();
        assert_eq!(error.to_string(), "not a folder (it is a file)");
        assert!(folders.allow(&dir.path().join("missing")).is_err());

        folders.allow_virtual(Path::new("no/such/folder"));
        let inside = folders
            .resolve(Path::new("no/such/folder"), Path::new("a.ron"))
            .unwrap();
        assert!(inside.lexical.ends_with("no/such/folder/a.ron"));
        assert!(inside.real.is_err());
        assert!(folders.to_string().ends_with("no/such/folder"), "{folders}");
    }
}
