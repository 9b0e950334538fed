//! The `--out` file: checked before any work, written atomically at the end.

use std::path::Path;

use image::codecs::png::PngEncoder;
use image::{ExtendedColorType, ImageEncoder, RgbaImage};

use super::error::RenderError;
use crate::commands::write_atomically;

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

/// Encodes the image (sRGB-encoded RGBA8) as a PNG and writes it through a temporary file
/// and a rename.
pub fn write_png(path: &Path, image: &RgbaImage) -> Result<(), RenderError> {
    let mut png = Vec::new();
    PngEncoder::new(&mut png)
        .write_image(
            image.as_raw(),
            image.width(),
            image.height(),
            ExtendedColorType::Rgba8,
        )
        .map_err(|e| RenderError::Output(format!("cannot encode {}: {e}", path.display())))?;
    write_atomically(path, &png).map_err(|e| RenderError::Output(e.to_string()))
}
