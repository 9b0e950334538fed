//! One module per subcommand, and what they share: errors with exit codes, atomic writes
//! of files and PNGs.

pub mod adapters;
pub mod bench;
pub mod explain;
pub mod render;
pub mod target;
pub mod validate;
pub mod view;

use std::io::Write;
use std::path::Path;
use std::process::ExitCode;

use image::codecs::png::PngEncoder;
use image::{ExtendedColorType, ImageEncoder, RgbaImage};

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

/// Writes `bytes` to `path` through a temporary file in the same directory and a rename,
/// so a failure never leaves a partial file behind under the real name.
pub fn write_atomically(path: &Path, bytes: &[u8]) -> Result<(), CommandError> {
    let io =
        |e: std::io::Error| CommandError::Usage(format!("cannot write {}: {e}", path.display()));
    let temp = partial_path(path)
        .ok_or_else(|| CommandError::Usage(format!("{} is not a file path", path.display())))?;
    let result = std::fs::File::create(&temp)
        .and_then(|mut f| f.write_all(bytes).and_then(|_| f.sync_all()))
        .and_then(|_| std::fs::rename(&temp, path));
    if result.is_err() {
        let _ = std::fs::remove_file(&temp);
    }
    result.map_err(io)
}

/// The temporary file [`write_atomically`] writes `path` through: `.NAME.partial` in the
/// same directory (so the rename stays on one file system). `None` when `path` names no file.
pub fn partial_path(path: &Path) -> Option<std::path::PathBuf> {
    let dir = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let name = path.file_name()?;
    Some(dir.join(format!(".{}.partial", name.to_string_lossy())))
}

/// Encodes the image (sRGB-encoded RGBA8) as a PNG and writes it through a temporary file
/// and a rename.
pub fn write_png(path: &Path, image: &RgbaImage) -> Result<(), CommandError> {
    let mut png = Vec::new();
    PngEncoder::new(&mut png)
        .write_image(
            image.as_raw(),
            image.width(),
            image.height(),
            ExtendedColorType::Rgba8,
        )
        .map_err(|e| CommandError::Usage(format!("cannot encode {}: {e}", path.display())))?;
    write_atomically(path, &png)
}
