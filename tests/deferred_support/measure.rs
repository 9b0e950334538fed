//! Image measurements the baseline tests share: differences in 8-bit units, edge masks
//! from the `debug.edges` view, and mean luminance over a mask.

use crate::deferred_support::Image;

/// The red of an edge pixel in `debug.edges` (stencil 0x80: shaded per sample).
pub const EDGE_RED: [u8; 4] = [255, 0, 0, 255];

/// How two images differ over the pixels of a mask, in 8-bit units of the RGB channels.
#[derive(Copy, Clone, Debug, Default)]
pub struct Diff {
    /// The largest channel difference.
    pub max: u8,
    /// Where it is.
    pub at: (u32, u32),
    /// The mean over the masked pixels' channels.
    pub mean: f64,
    /// How many pixels were compared.
    pub pixels: usize,
    /// How many of them differ at all.
    pub differing: usize,
}

impl std::fmt::Display for Diff {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "max {} at ({}, {}), mean {:.3} over {} pixels",
            self.max, self.at.0, self.at.1, self.mean, self.pixels
        )
    }
}

/// The largest RGB channel difference between two pixels.
pub fn pixel_diff(a: [u8; 4], b: [u8; 4]) -> u8 {
    (0..3).map(|c| a[c].abs_diff(b[c])).max().unwrap_or(0)
}

/// How many pixels of `a` and `b` differ by at most `tolerance` in every RGB channel.
pub fn pixels_within(a: &Image, b: &Image, tolerance: u8) -> usize {
    assert_eq!(
        (a.width, a.height),
        (b.width, b.height),
        "compared images differ in size"
    );
    (a.pixels.iter().zip(&b.pixels))
        .filter(|&(&p, &q)| pixel_diff(p, q) <= tolerance)
        .count()
}

/// How `a` and `b` differ where `mask` is true (everywhere for `None`).
pub fn diff(a: &Image, b: &Image, mask: Option<&[bool]>) -> Diff {
    assert_eq!(
        (a.width, a.height),
        (b.width, b.height),
        "compared images differ in size"
    );
    let mut d = Diff::default();
    let mut sum = 0u64;
    for (i, (pa, pb)) in a.pixels.iter().zip(&b.pixels).enumerate() {
        if mask.is_some_and(|m| !m[i]) {
            continue;
        }
        d.pixels += 1;
        sum += (0..3)
            .map(|c| u64::from(pa[c].abs_diff(pb[c])))
            .sum::<u64>();
        let worst = pixel_diff(*pa, *pb);
        d.differing += usize::from(worst > 0);
        if worst > d.max {
            d.max = worst;
            d.at = (i as u32 % a.width, i as u32 / a.width);
        }
    }
    d.mean = sum as f64 / (3 * d.pixels.max(1)) as f64;
    d
}

/// Where `debug.edges` is red: the pixels the edge detector marked.
pub fn marked(edges: &Image) -> Vec<bool> {
    edges.pixels.iter().map(|&p| p == EDGE_RED).collect()
}

/// The pixels of `edges` (a `debug.edges` view) none of whose 3x3 neighbours is an edge
/// pixel or empty (black: no geometry): away from every edge and silhouette, so that the
/// 2x2 quad a fragment shader computes derivatives over shows one surface.
pub fn away_from_edges(edges: &Image) -> Vec<bool> {
    let apart: Vec<bool> = edges
        .pixels
        .iter()
        .map(|&p| p == EDGE_RED || p == [0, 0, 0, 255])
        .collect();
    let (w, h) = (i64::from(edges.width), i64::from(edges.height));
    (0..h)
        .flat_map(|y| (0..w).map(move |x| (x, y)))
        .map(|(x, y)| {
            !(-1..=1).any(|dy| {
                (-1..=1).any(|dx| {
                    let (nx, ny) = (x + dx, y + dy);
                    nx >= 0 && ny >= 0 && nx < w && ny < h && apart[(ny * w + nx) as usize]
                })
            })
        })
        .collect()
}

/// Share of the pixels where `mask` is true (all for `None`) at which `a` and `b` differ
/// by at most `tolerance` in every RGB channel.
pub fn share_within(a: &Image, b: &Image, tolerance: u8, mask: Option<&[bool]>) -> f64 {
    assert_eq!(
        (a.width, a.height),
        (b.width, b.height),
        "compared images differ in size"
    );
    let (mut within, mut pixels) = (0usize, 0usize);
    for (i, (&p, &q)) in a.pixels.iter().zip(&b.pixels).enumerate() {
        if mask.is_none_or(|m| m[i]) {
            pixels += 1;
            within += usize::from(pixel_diff(p, q) <= tolerance);
        }
    }
    within as f64 / pixels.max(1) as f64
}

/// Pixel coordinates of the true entries, for messages (the first `limit`).
pub fn where_true(mask: &[bool], width: u32, limit: usize) -> Vec<(u32, u32)> {
    mask.iter()
        .enumerate()
        .filter(|(_, &m)| m)
        .take(limit)
        .map(|(i, _)| (i as u32 % width, i as u32 / width))
        .collect()
}

/// Rec. 709 luma of the 8-bit (sRGB-encoded) RGB values, averaged over `mask`.
pub fn mean_luma(image: &Image, mask: &[bool]) -> f64 {
    let (mut sum, mut n) = (0.0, 0usize);
    for (p, _) in image.pixels.iter().zip(mask).filter(|(_, &m)| m) {
        sum += 0.2126 * f64::from(p[0]) + 0.7152 * f64::from(p[1]) + 0.0722 * f64::from(p[2]);
        n += 1;
    }
    sum / n.max(1) as f64
}
