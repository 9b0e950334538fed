//! One module per subcommand, and what they share: errors with exit codes, atomic writes
//! of files and PNGs.

pub mod adapters;
pub mod bench;
pub mod compare;
pub mod explain;
pub mod render;
pub mod target;
pub mod validate;
pub mod view;

use std::io::Write;
use std::path::Path;
use std::process::ExitCode;

use image::RgbaImage;
use tempfile::NamedTempFile;

/// How a command failed, which decides the exit status.
#[derive(Debug, thiserror::Error)]
pub enum CommandError {
    /// The inputs were read and are wrong; the details were already printed. Exit 1.
    #[error("{0}")]
    Invalid(String),
    /// Usage, I/O or environment problems. Exit 2.
    #[error("{0}")]
    Usage(String),
}

impl CommandError {
    pub fn exit_code(&self) -> ExitCode {
        match self {
            CommandError::Invalid(_) => ExitCode::from(1),
            CommandError::Usage(_) => ExitCode::from(2),
        }
    }
}

/// Writes `bytes` to `path` through a temporary file beside it ([`temporary_beside`]) and
/// a rename, so a failure never leaves a partial file behind under the real name. Nothing
/// is written through a link: the temporary file is new, and a link at `path` itself is
/// replaced by the file, its target untouched.
pub fn write_atomically(path: &Path, bytes: &[u8]) -> Result<(), CommandError> {
    let io =
        |e: std::io::Error| CommandError::Usage(format!("cannot write {}: {e}", path.display()));
    let mut temp = temporary_beside(path).map_err(io)?;
    temp.write_all(bytes)
        .and_then(|_| temp.as_file().sync_all())
        .map_err(io)?;
    // Dropped on failure, the temporary file is deleted.
    temp.persist(path).map_err(|e| io(e.error))?;
    Ok(())
}

/// A new, empty file in `path`'s directory (so a rename onto `path` stays on one file
/// system), named `.NAME.RANDOM.partial` and created exclusively (`O_EXCL`): no name
/// another user could predict and plant a link at, and never an existing file. It gets
/// the permissions any new file gets (read-write for all, less the umask) and is deleted
/// when dropped unless persisted. An error when `path` names no file (`x.png/`, `/`).
pub fn temporary_beside(path: &Path) -> std::io::Result<NamedTempFile> {
    let name = path.file_name().ok_or_else(|| {
        std::io::Error::new(std::io::ErrorKind::InvalidInput, "the path names no file")
    })?;
    let dir = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let prefix = format!(".{}.", name.to_string_lossy());
    let mut builder = tempfile::Builder::new();
    builder.prefix(&prefix).suffix(".partial");
    #[cfg(unix)]
    builder.permissions(std::os::unix::fs::PermissionsExt::from_mode(0o666));
    builder.tempfile_in(dir)
}

/// `dir`, a folder of our own inside an output folder the user named: created when
/// missing, refused when something else (a link, say) stands at its name, so that the
/// files written in it land where the user asked.
pub fn own_folder(dir: &Path) -> std::io::Result<()> {
    match std::fs::symlink_metadata(dir) {
        Ok(meta) if meta.is_dir() => Ok(()),
        Ok(_) => Err(std::io::Error::new(
            std::io::ErrorKind::AlreadyExists,
            "something that is not a folder (a link or a file) is in the way",
        )),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => std::fs::create_dir(dir),
        Err(e) => Err(e),
    }
}

/// Encodes the image (sRGB-encoded RGBA8) as a PNG straight into a temporary file beside
/// `path` ([`temporary_beside`]) and renames it onto `path`. The encoder streams: it
/// holds a chunk of the compressed image at a time, never all of it, so a large image
/// needs no second copy of its size in memory.
pub fn write_png(path: &Path, image: &RgbaImage) -> Result<(), CommandError> {
    let failed = |e: &dyn std::fmt::Display| {
        CommandError::Usage(format!("cannot write {}: {e}", path.display()))
    };
    let mut temp = temporary_beside(path).map_err(|e| failed(&e))?;
    encode_png(std::io::BufWriter::new(temp.as_file_mut()), image).map_err(|e| failed(&e))?;
    temp.as_file().sync_all().map_err(|e| failed(&e))?;
    temp.persist(path).map_err(|e| failed(&e.error))?;
    Ok(())
}

/// `image` as an 8-bit RGBA PNG into `out`, row data streamed in chunks; flushes `out`.
fn encode_png(out: impl Write, image: &RgbaImage) -> Result<(), png::EncodingError> {
    let mut encoder = png::Encoder::new(out, image.width(), image.height());
    encoder.set_color(png::ColorType::Rgba);
    encoder.set_depth(png::BitDepth::Eight);
    // What the image crate's PNG encoder chooses by default.
    encoder.set_compression(png::Compression::Balanced);
    encoder.set_filter(png::Filter::Adaptive);
    let mut png = encoder.write_header()?;
    let mut rows = png.stream_writer()?;
    rows.write_all(image.as_raw())?;
    rows.finish()?;
    // The end chunk, and a flush of `out`.
    png.finish()
}
