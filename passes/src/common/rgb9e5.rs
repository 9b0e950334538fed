//! RGB9E5 on the CPU, bit for bit as common.wgsl's `pack_rgb9e5` and `unpack_rgb9e5`: the
//! lean G-buffer clears its emission channel to the background packed here.

/// The largest value a channel holds: (2^9 − 1) / 2^9 × 2^16.
pub const MAX: f32 = 65408.0;

/// Three 9-bit mantissas (red in the low bits) and a 5-bit exponent (EXT_texture_shared_exponent,
/// bias 15). Channels are clamped to `[0, MAX]`; NaN is 0.
pub fn pack(rgb: [f32; 3]) -> u32 {
    let c = rgb.map(|v| if v > 0.0 { v.min(MAX) } else { 0.0 });
    let brightest = c[0].max(c[1]).max(c[2]);
    if brightest <= 0.0 {
        return 0;
    }
    // floor(log2(brightest)), exactly: log2 may round across a power of two.
    let mut log2 = brightest.log2().floor() as i32;
    if 2f32.powi(log2) > brightest {
        log2 -= 1;
    } else if 2f32.powi(log2 + 1) <= brightest {
        log2 += 1;
    }
    let mut e = log2.max(-16) + 16;
    if (brightest * 2f32.powi(24 - e) + 0.5).floor() as u32 == 512 {
        e += 1;
    }
    let m = c.map(|v| (v * 2f32.powi(24 - e) + 0.5).floor() as u32);
    m[0] | (m[1] << 9) | (m[2] << 18) | ((e as u32) << 27)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// What [`pack`] packed (unpack_rgb9e5 in common.wgsl), each channel to within 2^-9 of the brightest one, or 2^-25
    /// below 2^-15 (the smallest exponent).
    fn unpack(bits: u32) -> [f32; 3] {
        let scale = 2f32.powi((bits >> 27) as i32 - 24);
        [bits & 511, (bits >> 9) & 511, (bits >> 18) & 511].map(|m| m as f32 * scale)
    }

    #[test]
    fn round_trips_within_a_ninth_bit_of_the_brightest_channel_or_the_smallest_step() {
        for rgb in [
            [1.0, 0.5, 0.25],
            [0.0, 0.0, 0.0],
            [65408.0, 1.0, 0.0],
            [1e-6, 2e-6, 0.0],
            [0.999, 0.998, 1.0],
            [3.7, 12.25, 0.01],
        ] {
            let back = unpack(pack(rgb));
            let brightest = rgb.iter().copied().fold(0.0f32, f32::max);
            for (a, b) in rgb.iter().zip(back) {
                assert!(
                    (a - b).abs() <= (brightest / 512.0).max(2f32.powi(-25)),
                    "{rgb:?} came back as {back:?}"
                );
            }
        }
    }

    #[test]
    fn clamps_what_it_cannot_hold() {
        assert_eq!(unpack(pack([1e9, -1.0, f32::NAN])), [MAX, 0.0, 0.0]);
    }

    #[test]
    fn powers_of_two_keep_their_exponent() {
        // 1.0 is mantissa 256 at exponent 16 (2^(16 - 24) * 256 = 1).
        assert_eq!(pack([1.0, 0.0, 0.0]), 256 | (16 << 27));
        assert_eq!(unpack(pack([0.5, 0.0, 0.0])), [0.5, 0.0, 0.0]);
    }
}
