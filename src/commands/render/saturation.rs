//! Whether the final image is blown out: the warning a user of physical light units (a
//! 68,000 lux sun at exposure 1) needs instead of a silent white frame.

use image::RgbaImage;

/// The share of lit pixels above which the render command warns.
pub const WARN_SHARE: f64 = 0.1;

/// The share of the image's lit (non-black) pixels with a colour channel at 255, if above
/// [`WARN_SHARE`]. Black pixels are background or unlit: they say nothing of exposure.
pub fn blown_out(image: &RgbaImage) -> Option<f64> {
    let (mut lit, mut saturated) = (0usize, 0usize);
    for pixel in image.pixels() {
        let rgb = &pixel.0[..3];
        if rgb.iter().any(|&c| c > 0) {
            lit += 1;
            saturated += usize::from(rgb.contains(&255));
        }
    }
    let share = saturated as f64 / lit.max(1) as f64;
    (share > WARN_SHARE).then_some(share)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_only_lit_pixels() {
        let mut image = RgbaImage::new(10, 10);
        // 10 lit pixels, 2 of them saturated: 20%.
        for x in 0..10 {
            image.put_pixel(x, 0, image::Rgba([100, 100, 100, 255]));
        }
        image.put_pixel(0, 0, image::Rgba([255, 10, 10, 255]));
        image.put_pixel(1, 0, image::Rgba([255, 255, 255, 255]));
        assert_eq!(blown_out(&image), Some(0.2));
        image.put_pixel(1, 0, image::Rgba([254, 254, 254, 255]));
        assert_eq!(blown_out(&image), None);
    }
}
