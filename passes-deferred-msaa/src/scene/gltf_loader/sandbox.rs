//! Resolving a glTF URI's path to a file inside the folders the [`AssetPolicy`] allows.

use std::path::{Component, Path, PathBuf};

use graph_core::bounded_read;

use super::uri_error::UriError;
use crate::scene::{AssetPolicy, SceneError};

/// The folders a glTF file's URIs may reach, canonical (symbolic links resolved), and the
/// size cap on each file read.
pub(super) struct Sandbox {
    /// The glTF file's folder, canonical: relative URIs start here.
    base: PathBuf,
    /// `base` and the policy's root, canonical.
    allowed: Vec<PathBuf>,
    max_bytes: u64,
}

impl Sandbox {
    /// The sandbox for the glTF file `file` under `policy`. Fails when the file's folder or
    /// the policy's root cannot be resolved (missing, unreadable).
    pub fn new(file: &Path, policy: &AssetPolicy) -> Result<Sandbox, SceneError> {
        let folder = match file.parent() {
            Some(parent) if !parent.as_os_str().is_empty() => parent,
            _ => Path::new("."),
        };
        let canonical = |dir: &Path| {
            dir.canonicalize().map_err(|source| SceneError::Io {
                file: dir.to_owned(),
                source: source.into(),
            })
        };
        let base = canonical(folder)?;
        let mut allowed = vec![base.clone()];
        if let Some(root) = &policy.root {
            allowed.push(canonical(root)?);
        }
        Ok(Sandbox {
            base,
            allowed,
            max_bytes: policy.max_bytes,
        })
    }

    /// Reads the file the (percent-decoded) URI path `relative` names. Errors are a reason
    /// naming `uri` when the path leaves the allowed folders, else a [`SceneError::Io`]
    /// naming the file.
    pub fn read(&self, uri: &str, relative: &Path) -> Result<Vec<u8>, UriError> {
        // First without touching the file system, so a path that leaves is refused with
        // the same message whether or not its target exists.
        let lexical = normalise(&self.base.join(relative));
        self.check(uri, &lexical, "points")?;
        // Then where it really is: a symbolic link inside the folder may lead out of it.
        let real = lexical.canonicalize().map_err(|source| {
            UriError::Io(SceneError::Io {
                file: lexical.clone(),
                source: source.into(),
            })
        })?;
        self.check(uri, &real, "leads (through a symbolic link)")?;
        bounded_read::read(&real, self.max_bytes).map_err(|source| {
            UriError::Io(SceneError::Io {
                file: lexical,
                source,
            })
        })
    }

    fn check(&self, uri: &str, path: &Path, how: &str) -> Result<(), UriError> {
        if self.allowed.iter().any(|dir| path.starts_with(dir)) {
            return Ok(());
        }
        let folders = self
            .allowed
            .iter()
            .map(|dir| dir.display().to_string())
            .collect::<Vec<_>>()
            .join(" or ");
        Err(UriError::Invalid(format!(
            "URI `{uri}` {how} to {}, outside the asset folder {folders}; assets only read \
             files inside their folder unless it is widened (--asset-root DIR)",
            path.display()
        )))
    }
}

/// `path` with `.` and `..` applied to its text (an absolute `path` stays absolute; `..` at
/// the root stays at the root, as the OS does).
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
