//! A tiny seeded PRNG (PCG32, XSH-RR variant) so built-in scenes are bit-identical on every run
//! and platform without a dependency whose stream might change between versions.

/// PCG32 by M. E. O'Neill: 64-bit LCG state, 32-bit permuted output.
pub(super) struct Pcg32 {
    state: u64,
    increment: u64,
}

impl Pcg32 {
    const MULTIPLIER: u64 = 6364136223846793005;
    /// The reference implementation's default stream.
    const STREAM: u64 = 1442695040888963407;

    /// Seeds like the reference `pcg32_srandom_r`.
    pub fn new(seed: u64) -> Pcg32 {
        let mut rng = Pcg32 {
            state: 0,
            increment: Self::STREAM | 1,
        };
        rng.next_u32();
        rng.state = rng.state.wrapping_add(seed);
        rng.next_u32();
        rng
    }

    pub fn next_u32(&mut self) -> u32 {
        let old = self.state;
        self.state = old
            .wrapping_mul(Self::MULTIPLIER)
            .wrapping_add(self.increment);
        let xorshifted = (((old >> 18) ^ old) >> 27) as u32;
        xorshifted.rotate_right((old >> 59) as u32)
    }

    /// Uniform in `[0, 1)`, from the top 24 bits (exactly representable in f32).
    pub fn unit(&mut self) -> f32 {
        (self.next_u32() >> 8) as f32 * (1.0 / (1u32 << 24) as f32)
    }

    /// Uniform in `[low, high)`.
    pub fn range(&mut self, low: f32, high: f32) -> f32 {
        low + (high - low) * self.unit()
    }
}
