//! Why a glTF buffer's or image's URI could not be read: its own file, so the URI reader
//! and the sandbox it reads through both name it without importing each other.

use crate::SceneError;

/// Why reading a URI failed (`uri::read`, `Sandbox::read`).
pub(super) enum UriError {
    /// The URI itself is unusable; the caller says which object had it.
    Invalid(String),
    /// The referenced file could not be read; already names the file.
    Io(SceneError),
}

impl UriError {
    /// The scene error, with `invalid` naming the object whose URI failed either way: a
    /// missing file's user needs the glTF file and the buffer or image that refers to it, not
    /// only the file.
    pub(super) fn into_named_error(self, invalid: impl FnOnce(String) -> SceneError) -> SceneError {
        match self {
            UriError::Invalid(reason) => invalid(reason),
            UriError::Io(error) => invalid(error.to_string()),
        }
    }
}
