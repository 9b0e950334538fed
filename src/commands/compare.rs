//! `rgraph compare`: how close two rendered images are, for golden-image checks in CI and
//! for comparing pipelines on a machine without Rust (the GPU server): the share of
//! pixels within a tolerance in every channel, the worst difference and where it is, and
//! mean FLIP.

use std::path::Path;

use image::{ImageReader, Limits, RgbaImage};

use super::bench::image_error::flip_mean;
use super::CommandError;

/// The largest side an image to compare may have: the largest texture a render makes.
const MAX_SIDE: u32 = 16384;

/// What two images of one size differ by.
#[derive(Debug, PartialEq)]
pub struct Difference {
    /// Pixels whose every channel (alpha included) differs by at most the tolerance.
    pub within: u64,
    pub pixels: u64,
    /// The largest difference of one channel, 0 to 255, and the first pixel that has it.
    pub worst: u8,
    pub worst_at: (u32, u32),
}

impl Difference {
    pub fn of(a: &RgbaImage, b: &RgbaImage, tolerance: u8) -> Difference {
        let mut difference = Difference {
            within: 0,
            pixels: u64::from(a.width()) * u64::from(a.height()),
            worst: 0,
            worst_at: (0, 0),
        };
        for ((x, y, p), q) in a.enumerate_pixels().zip(b.pixels()) {
            let most = (0..4).map(|c| p.0[c].abs_diff(q.0[c])).max().unwrap_or(0);
            difference.within += u64::from(most <= tolerance);
            if most > difference.worst {
                (difference.worst, difference.worst_at) = (most, (x, y));
            }
        }
        difference
    }

    /// The share within the tolerance, in percent.
    pub fn percent(&self) -> f64 {
        100.0 * self.within as f64 / self.pixels.max(1) as f64
    }
}

/// Compares `a` with `b`; an error (exit 1) when fewer than `at_least` percent of the
/// pixels are within `tolerance` or the sizes differ, exit 2 when a file cannot be read.
pub fn run(a: &Path, b: &Path, tolerance: u8, at_least: f64) -> Result<(), CommandError> {
    if !(0.0..=100.0).contains(&at_least) {
        return Err(CommandError::Usage(format!(
            "--at-least is {at_least}, but must be a percentage from 0 to 100"
        )));
    }
    let (first, second) = (read(a)?, read(b)?);
    if first.dimensions() != second.dimensions() {
        let size = |i: &RgbaImage| format!("{}x{}", i.width(), i.height());
        let message = format!(
            "{} is {} but {} is {}: only images of one size compare",
            a.display(),
            size(&first),
            b.display(),
            size(&second)
        );
        eprintln!("error: {message}");
        return Err(CommandError::Invalid(message));
    }
    let difference = Difference::of(&first, &second, tolerance);
    let (x, y) = difference.worst_at;
    println!(
        "{:.3}% of {} pixels within {tolerance}/255 in every channel; worst {}/255 at ({x}, {y}); \
         mean FLIP {:.4}",
        difference.percent(),
        difference.pixels,
        difference.worst,
        flip_mean(&first, &second)
    );
    match difference.percent() >= at_least {
        true => Ok(()),
        false => {
            let message = format!(
                "the images differ: {:.3}% of pixels within {tolerance}/255, fewer than \
                 --at-least {at_least}%",
                difference.percent()
            );
            eprintln!("error: {message}");
            Err(CommandError::Invalid(message))
        }
    }
}

/// Reads a PNG, refusing one whose header says
/// it is larger than [`MAX_SIDE`] before decoding it.
fn read(path: &Path) -> Result<RgbaImage, CommandError> {
    let failed =
        |why: String| CommandError::Usage(format!("cannot read {}: {why}", path.display()));
    let mut reader = ImageReader::open(path)
        .map_err(|e| failed(e.to_string()))?
        .with_guessed_format()
        .map_err(|e| failed(e.to_string()))?;
    let mut limits = Limits::default();
    limits.max_image_width = Some(MAX_SIDE);
    limits.max_image_height = Some(MAX_SIDE);
    // Four bytes a pixel at the largest size, and the decoder's own buffers.
    limits.max_alloc = Some(2 * 4 * u64::from(MAX_SIDE) * u64::from(MAX_SIDE));
    reader.limits(limits);
    let image = reader.decode().map_err(|e| failed(e.to_string()))?;
    Ok(image.into_rgba8())
}

#[cfg(test)]
mod tests {
    use image::{Rgba, RgbaImage};

    use super::Difference;

    #[test]
    fn counts_pixels_within_the_tolerance_and_finds_the_worst() {
        let a = RgbaImage::from_pixel(4, 2, Rgba([10, 20, 30, 255]));
        let mut b = a.clone();
        b.put_pixel(1, 0, Rgba([11, 20, 30, 255]));
        b.put_pixel(3, 1, Rgba([10, 20, 30, 250]));
        let difference = Difference::of(&a, &b, 1);
        assert_eq!(
            difference,
            Difference {
                within: 7,
                pixels: 8,
                worst: 5,
                worst_at: (3, 1)
            }
        );
        assert_eq!(difference.percent(), 87.5);
        assert_eq!(Difference::of(&a, &b, 5).within, 8);
    }
}
