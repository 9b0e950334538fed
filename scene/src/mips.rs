//! Mipmaps of a texture image, made on the CPU before upload: minified textures then
//! filter instead of aliasing (a checker seen from afar is grey, not moiré).
//!
//! Each level halves the one above, rounding down and keeping at least one texel, and
//! each texel is the mean of the 2x2 block above it (an odd side's last row or column
//! is left out; a side of 1 stays 1, its texels counted twice). sRGB images are averaged in linear light, as a GPU filters
//! them, so a black-and-white checker minifies to 188 in sRGB, the encoding of 0.5, not
//! to 128; alpha and linear images are averaged as stored.

use std::sync::LazyLock;

use super::TextureImage;

impl TextureImage {
    /// How many levels a full chain has: down to 1x1.
    pub fn mip_levels(&self) -> u32 {
        32 - self.width.max(self.height).max(1).leading_zeros()
    }

    /// Every level below the image itself, largest first, as RGBA8 bytes.
    pub fn mip_chain(&self) -> Vec<Vec<u8>> {
        let mut levels: Vec<Vec<u8>> = Vec::new();
        let (mut width, mut height) = (self.width, self.height);
        for _ in 1..self.mip_levels() {
            let above = levels.last().unwrap_or(&self.rgba8);
            let next = self.halve(above, width, height);
            width = (width / 2).max(1);
            height = (height / 2).max(1);
            levels.push(next);
        }
        levels
    }

    /// The level below `texels` (`width` x `height`).
    fn halve(&self, texels: &[u8], width: u32, height: u32) -> Vec<u8> {
        let (w, h) = ((width / 2).max(1), (height / 2).max(1));
        let at = |x: u32, y: u32, c: usize| {
            let (x, y) = (x.min(width - 1), y.min(height - 1));
            texels[((y * width + x) * 4) as usize + c]
        };
        let mut out = Vec::with_capacity((w * h * 4) as usize);
        for y in 0..h {
            for x in 0..w {
                for c in 0..4 {
                    let block = [(0, 0), (1, 0), (0, 1), (1, 1)]
                        .map(|(dx, dy)| at(2 * x + dx, 2 * y + dy, c));
                    out.push(self.mean(block, c == 3));
                }
            }
        }
        out
    }

    /// The mean of four stored values of one channel.
    fn mean(&self, values: [u8; 4], alpha: bool) -> u8 {
        if self.srgb && !alpha {
            let linear: f64 = values.iter().map(|&v| srgb_to_linear(v)).sum::<f64>() / 4.0;
            linear_to_srgb(linear)
        } else {
            let sum: u32 = values.iter().map(|&v| u32::from(v)).sum();
            ((sum + 2) / 4) as u8
        }
    }
}

/// An sRGB-encoded 8-bit value in linear light, 0 to 1: read from a table of the 256
/// decodings, made once (mip-mapping a model's textures decoded each texel four times,
/// a `powf` each, most of a textured model's load).
pub(crate) fn srgb_to_linear(v: u8) -> f64 {
    static DECODED: LazyLock<[f64; 256]> = LazyLock::new(|| {
        std::array::from_fn(|v| {
            let c = v as f64 / 255.0;
            if c <= 0.04045 {
                c / 12.92
            } else {
                ((c + 0.055) / 1.055).powf(2.4)
            }
        })
    });
    DECODED[usize::from(v)]
}

/// Linear light (clamped to 0..=1 after encoding) as an sRGB-encoded 8-bit value.
pub(crate) fn linear_to_srgb(l: f64) -> u8 {
    let c = if l <= 0.0031308 {
        l * 12.92
    } else {
        1.055 * l.powf(1.0 / 2.4) - 0.055
    };
    (c * 255.0).round().clamp(0.0, 255.0) as u8
}

#[cfg(test)]
mod tests {
    use super::*;

    fn image(
        width: u32,
        height: u32,
        srgb: bool,
        texel: impl Fn(u32, u32) -> [u8; 4],
    ) -> TextureImage {
        let rgba8 = (0..height)
            .flat_map(|y| (0..width).map(move |x| (x, y)))
            .flat_map(|(x, y)| texel(x, y))
            .collect();
        TextureImage {
            name: "test".into(),
            width,
            height,
            rgba8,
            srgb,
        }
    }

    fn checker(x: u32, y: u32) -> [u8; 4] {
        let v = if (x + y).is_multiple_of(2) { 255 } else { 0 };
        [v, v, v, 255]
    }

    #[test]
    fn levels_halve_down_to_one_texel() {
        let img = image(8, 3, true, checker);
        assert_eq!(img.mip_levels(), 4);
        let sizes: Vec<usize> = img.mip_chain().iter().map(Vec::len).collect();
        // 4x1, 2x1, 1x1 texels of 4 bytes.
        assert_eq!(sizes, [16, 8, 4]);
        assert_eq!(image(1, 1, true, checker).mip_chain().len(), 0);
    }

    #[test]
    fn an_srgb_checker_averages_in_linear_light() {
        let chain = image(4, 4, true, checker).mip_chain();
        for level in &chain {
            for texel in level.chunks_exact(4) {
                assert_eq!(texel, [188, 188, 188, 255]);
            }
        }
    }

    #[test]
    fn linear_data_and_alpha_average_as_stored() {
        let img = image(2, 2, false, |x, _| {
            if x == 0 {
                [255, 0, 10, 0]
            } else {
                [0, 255, 20, 255]
            }
        });
        assert_eq!(img.mip_chain(), [vec![128, 128, 15, 128]]);
    }
}
