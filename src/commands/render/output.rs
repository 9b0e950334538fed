//! The `--out` file: checked before any work, written atomically at the end.

use std::path::Path;

use image::RgbaImage;

use super::error::RenderError;

/// A `.png` path in an existing directory, so a long render never ends in an
/// unwritable path.
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
    Ok(())
}

/// Writes the image as a PNG, atomically.
pub fn write_png(path: &Path, image: &RgbaImage) -> Result<(), RenderError> {
    crate::commands::write_png(path, image).map_err(|e| RenderError::Output(e.to_string()))
}
