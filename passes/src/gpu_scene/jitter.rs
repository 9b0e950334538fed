//! Sub-pixel jitter of the camera for temporal anti-aliasing: each frame's projection is
//! offset by a point of the Halton(2, 3) sequence, so that a pixel's samples over frames
//! cover it evenly and a temporal filter that averages them converges to the pixel's box
//! average, as a supersampled image's does.

/// Frames in the cycle of offsets: 16, so that a still image averaged over a cycle holds
/// as many positions per pixel as the 16-sample reference (pipelines/reference_ssaa16.ron).
pub const JITTER_CYCLE: u64 = 16;

/// The offset of frame `frame`, in pixels, x right and y down, each in [-0.5, 0.5): the
/// Halton(2, 3) point of index `frame % JITTER_CYCLE + 1` (index 0 is the corner, which
/// the sequence otherwise visits never again), minus one half.
pub fn jitter(frame: u64) -> [f32; 2] {
    let index = frame % JITTER_CYCLE + 1;
    [halton(index, 2) - 0.5, halton(index, 3) - 0.5]
}

/// The radical inverse of `index` in `base`: its digits mirrored about the point.
fn halton(mut index: u64, base: u64) -> f32 {
    let (mut value, mut scale) = (0.0f64, 1.0f64);
    while index > 0 {
        scale /= base as f64;
        value += (index % base) as f64 * scale;
        index /= base;
    }
    value as f32
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn halton_points_are_the_radical_inverses() {
        assert_eq!(halton(1, 2), 0.5);
        assert_eq!(halton(6, 2), 0.375);
        assert_eq!(halton(1, 3), 1.0 / 3.0);
        assert_eq!(halton(5, 3), 7.0 / 9.0);
        assert_eq!(jitter(0), [0.0, 1.0 / 3.0 - 0.5]);
        assert_eq!(jitter(JITTER_CYCLE), jitter(0));
    }

    #[test]
    fn a_cycle_spreads_over_the_pixel_about_its_centre() {
        let mut quarters = [0; 4];
        let mut mean = [0.0f32; 2];
        for frame in 0..JITTER_CYCLE {
            let [x, y] = jitter(frame);
            assert!((-0.5..0.5).contains(&x) && (-0.5..0.5).contains(&y));
            quarters[usize::from(x >= 0.0) + 2 * usize::from(y >= 0.0)] += 1;
            mean = [mean[0] + x, mean[1] + y];
        }
        // Indices 1 to 16: base 2 splits the pixel evenly, base 3 nearly so.
        assert_eq!(quarters, [4, 5, 4, 3], "{quarters:?}");
        let mean = mean.map(|m| m / JITTER_CYCLE as f32);
        assert!(mean.iter().all(|m| m.abs() < 0.04), "mean offset {mean:?}");
    }
}
