//! The `--out` file: checked before any work, written atomically at the end.

use std::path::Path;

use image::RgbaImage;

use super::error::RenderError;
use crate::commands::partial_path;

/// A `.png` path in an existing directory that can be written, so a long render never
/// ends in an unwritable path.
pub fn check(path: &Path) -> Result<(), RenderError> {
    let shown = path.display();
    let is_png = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("png"));
    if !is_png {
        return Err(RenderError::Output(format!(
            "--out {shown}: the output must be a .png file"
        )));
    }
    if path.is_dir() {
        return Err(RenderError::Output(format!(
            "--out {shown}: is a directory; name a .png file"
        )));
    }
    let dir = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    if !dir.is_dir() {
        return Err(RenderError::Output(format!(
            "--out {shown}: directory {} does not exist",
            dir.display()
        )));
    }
    // Creating the temporary file the PNG is written through is the only sure test that
    // it can be written (permissions, read-only or full file systems, ACLs).
    let probe = partial_path(path)
        .ok_or_else(|| RenderError::Output(format!("--out {shown}: is not a file path")))?;
    std::fs::File::create(&probe)
        .and_then(|_| std::fs::remove_file(&probe))
        .map_err(|e| {
            RenderError::Output(format!(
                "--out {shown}: cannot write in {}: {e}",
                dir.display()
            ))
        })
}

/// Writes the image as a PNG, atomically.
pub fn write_png(path: &Path, image: &RgbaImage) -> Result<(), RenderError> {
    crate::commands::write_png(path, image).map_err(|e| RenderError::Output(e.to_string()))
}
