//! Resolving a glTF URI's path to a file inside the folders the [`AssetPolicy`] allows,
//! through the containment check graph files' references share ([`Folders`]).

use std::path::{Path, PathBuf};

use rgraph_core::bounded_read;
use rgraph_core::folders::{Folders, Inside};

use super::uri_error::UriError;
use crate::{AssetPolicy, SceneError};

/// The folders a glTF file's URIs may reach, and the size cap on each file read.
pub(super) struct Sandbox {
    /// The glTF file's folder: relative URIs start here.
    base: PathBuf,
    /// `base` and the policy's root.
    allowed: Folders,
    max_bytes: u64,
}

impl Sandbox {
    /// The sandbox for the glTF file `file` under `policy`. Fails when the file's folder or
    /// the policy's root cannot be resolved (missing, unreadable, not a folder).
    pub fn new(file: &Path, policy: &AssetPolicy) -> Result<Sandbox, SceneError> {
        let base = match file.parent() {
            Some(parent) if !parent.as_os_str().is_empty() => parent,
            _ => Path::new("."),
        };
        let mut allowed = Folders::new();
        for dir in std::iter::once(base).chain(policy.root.as_deref()) {
            allowed.allow(dir).map_err(|source| SceneError::Io {
                file: dir.to_owned(),
                source: source.into(),
            })?;
        }
        Ok(Sandbox {
            base: base.to_owned(),
            allowed,
            max_bytes: policy.max_bytes,
        })
    }

    /// Reads the file the (percent-decoded) URI path `relative` names. Errors are a reason
    /// naming `uri` when the path leaves the allowed folders, else a [`SceneError::Io`]
    /// naming the file.
    pub fn read(&self, uri: &str, relative: &Path) -> Result<Vec<u8>, UriError> {
        let inside = self
            .allowed
            .resolve(&self.base, relative)
            .map_err(|outside| {
                UriError::Invalid(format!(
                    "URI `{uri}` {outside}, outside the asset folder {}; assets only read files \
                 inside their folder unless it is widened (--asset-root DIR)",
                    self.allowed
                ))
            })?;
        let Inside { lexical, real } = inside;
        let io = |source| {
            UriError::Io(SceneError::Io {
                file: lexical.clone(),
                source,
            })
        };
        let real = real.map_err(|e| io(e.into()))?;
        bounded_read::read(&real, self.max_bytes).map_err(io)
    }
}
