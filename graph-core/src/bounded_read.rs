//! Reading files a user named, with a size cap and only from regular files.
//!
//! Every file path in a user's input (a graph file, a shader it names, a glTF file and the
//! buffers and images that points at) goes through here, so `/dev/zero` cannot exhaust
//! memory and a FIFO cannot block the process forever.

use std::io::Read;
use std::path::Path;

/// The largest graph file (.ron) read: 16 MiB, a thousand times the largest shipped one.
pub const MAX_GRAPH_FILE_BYTES: u64 = 16 << 20;

/// The largest WGSL shader read: 16 MiB.
pub const MAX_SHADER_BYTES: u64 = 16 << 20;

/// Why a bounded read failed. The messages do not name the file: callers do, with the role
/// the file plays (graph file, shader, glTF buffer, ...).
#[derive(Debug, thiserror::Error)]
pub enum ReadError {
    /// Opening or reading failed (the operating system's error).
    #[error("{0}")]
    Io(#[from] std::io::Error),
    /// A directory, FIFO, socket or device: reading one may never end (a FIFO blocks, a
    /// device like /dev/zero never reaches its end), so only regular files are read.
    #[error("not a regular file (it is a {kind})")]
    NotAFile {
        /// What it is: "directory", "FIFO", ...
        kind: &'static str,
    },
    /// Larger than the stated maximum.
    #[error("larger than the maximum of {max} bytes")]
    TooLarge {
        /// The maximum, in bytes.
        max: u64,
    },
    /// Not UTF-8 text (only from [`read_text`]).
    #[error("not UTF-8 text: {0}")]
    NotUtf8(std::string::FromUtf8Error),
}

/// Reads the whole regular file at `path` (symbolic links followed), refusing anything that
/// is not a regular file and anything over `max_bytes` before reading it all.
pub fn read(path: &Path, max_bytes: u64) -> Result<Vec<u8>, ReadError> {
    // Checked before opening: opening a FIFO for reading blocks until a writer appears.
    check_regular(&std::fs::metadata(path)?)?;
    let file = std::fs::File::open(path)?;
    // Checked again on the open file, in case the path was replaced in between.
    let metadata = file.metadata()?;
    check_regular(&metadata)?;
    if metadata.len() > max_bytes {
        return Err(ReadError::TooLarge { max: max_bytes });
    }
    // The length may change while reading (or lie, as on some virtual file systems): the
    // read itself stops one byte past the cap.
    let mut bytes = Vec::with_capacity(metadata.len() as usize);
    file.take(max_bytes.saturating_add(1))
        .read_to_end(&mut bytes)?;
    if bytes.len() as u64 > max_bytes {
        return Err(ReadError::TooLarge { max: max_bytes });
    }
    Ok(bytes)
}

/// [`read`], as UTF-8 text.
pub fn read_text(path: &Path, max_bytes: u64) -> Result<String, ReadError> {
    String::from_utf8(read(path, max_bytes)?).map_err(ReadError::NotUtf8)
}

fn check_regular(metadata: &std::fs::Metadata) -> Result<(), ReadError> {
    let kind = metadata.file_type();
    if kind.is_file() {
        return Ok(());
    }
    Err(ReadError::NotAFile {
        kind: file_type_name(&kind),
    })
}

/// What a non-regular file is, in words.
fn file_type_name(kind: &std::fs::FileType) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if kind.is_fifo() {
            return "FIFO";
        }
        if kind.is_char_device() {
            return "character device";
        }
        if kind.is_block_device() {
            return "block device";
        }
        if kind.is_socket() {
            return "socket";
        }
    }
    if kind.is_dir() {
        "directory"
    } else {
        "special file"
    }
}

#[cfg(test)]
mod tests {
    use super::{read, read_text, ReadError};
    use std::path::Path;

    fn temp(name: &str, bytes: &[u8]) -> std::path::PathBuf {
        let dir = std::env::temp_dir().join(format!("bounded-read-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join(name);
        std::fs::write(&path, bytes).unwrap();
        path
    }

    #[test]
    fn a_file_at_the_cap_is_read_and_one_byte_more_is_refused() {
        let path = temp("ten", b"0123456789");
        assert_eq!(read(&path, 10).unwrap(), b"0123456789");
        let error = read(&path, 9).unwrap_err();
        assert!(matches!(error, ReadError::TooLarge { max: 9 }), "{error:?}");
        assert_eq!(error.to_string(), "larger than the maximum of 9 bytes");
    }

    #[cfg(unix)]
    #[test]
    fn devices_and_directories_are_refused_without_reading() {
        let error = read(Path::new("/dev/zero"), 1 << 30).unwrap_err();
        assert_eq!(
            error.to_string(),
            "not a regular file (it is a character device)"
        );
        let error = read(&std::env::temp_dir(), 1 << 30).unwrap_err();
        assert_eq!(error.to_string(), "not a regular file (it is a directory)");
    }

    #[test]
    fn text_must_be_utf8() {
        let path = temp("latin1", b"caf\xe9");
        let error = read_text(&path, 100).unwrap_err();
        assert!(error.to_string().starts_with("not UTF-8 text"), "{error}");
    }
}
