//! The page's colours: a hue per physical allocation and per pass, the golden angle apart
//! so that neighbours differ, shared by the timeline and the time strip.

/// A hue per index, the golden angle apart, starting at `offset`.
pub(super) fn hue(index: usize, offset: f64) -> u32 {
    ((index as f64 * 137.508 + offset) % 360.0) as u32
}

/// The hue of pass `index`'s segment in the time strip.
pub(super) fn pass_hue(index: usize) -> u32 {
    hue(index, 90.0)
}
