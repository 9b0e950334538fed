//! The `--out` file, or with `--frames N` the pattern of one file per frame: checked
//! before any work, each written atomically.

use std::path::{Path, PathBuf};

use image::RgbaImage;

use super::error::RenderError;
use crate::commands::temporary_beside;

/// A `.png` path in an existing directory that can be written, so a long render never
/// ends in an unwritable path. `flag` names the option it came from in the errors.
pub fn check(path: &Path, flag: &str) -> Result<(), RenderError> {
    let shown = path.display();
    let is_png = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("png"));
    if !is_png {
        return Err(RenderError::Output(format!(
            "{flag} {shown}: the output must be a .png file"
        )));
    }
    if path.is_dir() {
        return Err(RenderError::Output(format!(
            "{flag} {shown}: is a directory; name a .png file"
        )));
    }
    let dir = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    if !dir.is_dir() {
        return Err(RenderError::Output(format!(
            "{flag} {shown}: directory {} does not exist",
            dir.display()
        )));
    }
    if path.file_name().is_none() {
        return Err(RenderError::Output(format!(
            "{flag} {shown}: is not a file path"
        )));
    }
    // Creating a temporary file as the PNG will be written through is the only sure test
    // that it can be written (permissions, read-only or full file systems, ACLs); dropped,
    // it is deleted.
    temporary_beside(path).map(drop).map_err(|e| {
        RenderError::Output(format!(
            "{flag} {shown}: cannot write in {}: {e}",
            dir.display()
        ))
    })
}

/// Writes the image as a PNG, atomically.
pub fn write_png(path: &Path, image: &RgbaImage) -> Result<(), RenderError> {
    crate::commands::write_png(path, image).map_err(|e| RenderError::Output(e.to_string()))
}

/// Where each frame's PNG goes: `--out` itself for one frame without a pattern, else
/// `--out` with its `%0Nd` (or `%d`) replaced by the frame number, zero-padded to N digits.
pub struct FramePaths {
    /// The path before the pattern, the pattern's width, the path after it.
    pattern: Option<(String, usize, String)>,
    out: PathBuf,
}

impl FramePaths {
    /// Checks `out` for `frames` frames: more than one needs a pattern, and the first
    /// frame's path must be writable (the others share its directory).
    pub fn new(out: &Path, frames: u32) -> Result<FramePaths, RenderError> {
        let shown = out.display();
        let text = out.to_str().ok_or_else(|| {
            RenderError::Output(format!("--out {shown}: the path is not valid UTF-8"))
        })?;
        let pattern = frame_pattern(text)
            .map_err(|why| RenderError::Output(format!("--out {shown}: {why}")))?;
        if pattern.is_none() && frames > 1 {
            return Err(RenderError::Output(format!(
                "--out {shown}: --frames {frames} writes one PNG per frame; put %04d (or \
                 %0Nd for N digits) in the file name where the frame number goes, e.g. \
                 out/frame_%04d.png"
            )));
        }
        let paths = FramePaths {
            pattern,
            out: out.to_path_buf(),
        };
        check(&paths.path(0), "--out")?;
        Ok(paths)
    }

    /// The PNG of frame `index`.
    pub fn path(&self, index: u32) -> PathBuf {
        match &self.pattern {
            Some((before, width, after)) => {
                PathBuf::from(format!("{before}{index:0width$}{after}"))
            }
            None => self.out.clone(),
        }
    }
}

/// The widest frame number `%0Nd` pads to: a frame number has at most 10 digits, and a
/// file name at most 255 bytes.
const MAX_WIDTH: usize = 32;

/// `text` split at its first `%0Nd` or `%d` (width 0: no padding); an error for a width
/// above [`MAX_WIDTH`].
fn frame_pattern(text: &str) -> Result<Option<(String, usize, String)>, String> {
    let Some(start) = text.find('%') else {
        return Ok(None);
    };
    let rest = &text[start + 1..];
    let digits = rest.bytes().take_while(u8::is_ascii_digit).count();
    if rest.as_bytes().get(digits) != Some(&b'd') {
        return Ok(None);
    }
    let width = match &rest[..digits] {
        "" => 0,
        padded if padded.starts_with('0') => {
            let width = padded.trim_start_matches('0');
            match width.parse::<usize>() {
                Ok(width) if width <= MAX_WIDTH => width,
                _ if width.is_empty() => 0,
                _ => {
                    return Err(format!(
                        "%{padded}d pads the frame number to {width} digits; at most \
                         {MAX_WIDTH} (%04d pads to 4)"
                    ))
                }
            }
        }
        // %4d pads with spaces in printf, which no file name wants.
        _ => return Ok(None),
    };
    let after = &rest[digits + 1..];
    Ok(Some((text[..start].to_string(), width, after.to_string())))
}

#[cfg(test)]
mod tests {
    use super::frame_pattern;

    #[test]
    fn frame_patterns() {
        let split = |text| frame_pattern(text).expect("a width within the bound");
        assert_eq!(
            split("out/%04d.png"),
            Some(("out/".into(), 4, ".png".into()))
        );
        assert_eq!(split("f%d.png"), Some(("f".into(), 0, ".png".into())));
        assert_eq!(split("f%00d.png"), Some(("f".into(), 0, ".png".into())));
        assert_eq!(split("f%032d.png"), Some(("f".into(), 32, ".png".into())));
        assert_eq!(split("out/frame.png"), None);
        assert_eq!(split("out/%4d.png"), None);
        assert_eq!(split("out/%s.png"), None);
    }

    #[test]
    fn widths_beyond_the_bound_are_errors_naming_it() {
        for text in [
            "f%033d.png",
            "f%065536d.png",
            "f%099999999999999999999999d.png",
        ] {
            let why = frame_pattern(text).expect_err(text);
            assert!(why.contains("at most 32"), "{text}: {why}");
        }
        let why = frame_pattern("f%065536d.png").unwrap_err();
        assert!(
            why.starts_with("%065536d pads the frame number to 65536 digits"),
            "{why}"
        );
    }
}
