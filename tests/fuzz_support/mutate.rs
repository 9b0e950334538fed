//! Mutations of an input: what a hostile or careless user (or a corrupted download) does to
//! a file. Byte-level edits, tokens of the formats at random places, numbers replaced by
//! extreme ones, and splices of two inputs.

/// A small, fast, seeded generator (xorshift64*): runs are reproducible from the seed.
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Rng {
        Rng(seed.max(1))
    }

    pub fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }

    /// Uniform in `0..n` (`n > 0`).
    pub fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }

    pub fn pick<'a, T>(&mut self, items: &'a [T]) -> &'a T {
        &items[self.below(items.len())]
    }
}

/// Tokens that matter to RON, JSON and the command line, and values at the edges.
const TOKENS: &[&str] = &[
    "(",
    ")",
    "[",
    "]",
    "{",
    "}",
    ",",
    ":",
    "\"",
    "\\",
    "/*",
    "//",
    "\n",
    "\u{feff}",
    "r#",
    "Some(",
    "NaN",
    "inf",
    "-inf",
    "-1",
    "0",
    "1e39",
    "-1e39",
    "1e308",
    "4294967295",
    "4294967296",
    "18446744073709551616",
    "65535",
    "65536",
    "16384",
    "0.0",
    "-0.0",
    "1e-45",
    "null",
    "true",
    "[]",
    "{}",
    "\"\"",
    "Relative(0.0)",
    "Relative(1e9)",
    "Absolute(0, 0)",
    "Absolute(65536, 65536)",
    "Workgroups(0, 0, 0)",
    "Workgroups(65536, 1, 1)",
    "samples: 64",
    "\"../../../../etc/passwd\"",
    "\"/dev/zero\"",
    // Graph-file references that leave the folders graph files may read (the fuzz target
    // plants the secret files they name).
    "\"/tmp/rgraph-fuzz-secret/secret.ron\"",
    "\"../../../../../../../../tmp/rgraph-fuzz-secret/secret.wgsl\"",
    "\"\\u{0}\"",
    "base: ",
    "shader: ",
    "Preset(base: \"../../../../../../../../tmp/rgraph-fuzz-secret/secret.ron\")",
    "mips: 2048",
    ", when: \"blend\"",
    "--graph-root",
    "--exposure",
    "1e25",
    "\"data:,\"",
    "\"%2e%2e/x.bin\"",
    "builtin:lights?count=100000000",
    "--width",
    "0",
    "--asset-root",
    "--max-asset-bytes",
];

/// `input` changed by one to four mutations; `other` may be spliced in.
pub fn mutate(rng: &mut Rng, input: &[u8], other: &[u8]) -> Vec<u8> {
    let mut out = input.to_vec();
    for _ in 0..=rng.below(4) {
        let at = rng.below(out.len() + 1);
        match rng.below(8) {
            0 if !out.is_empty() => {
                let i = rng.below(out.len());
                out[i] ^= 1 << rng.below(8);
            }
            1 if !out.is_empty() => {
                let end = (at + 1 + rng.below(16)).min(out.len());
                out.drain(at.min(end)..end);
            }
            2 if at < out.len() => {
                let end = (at + 1 + rng.below(64)).min(out.len());
                let copy = out[at..end].to_vec();
                out.splice(at..at, copy);
            }
            3 if !other.is_empty() => {
                // The head of this input and the tail of the other one.
                let from = rng.below(other.len());
                out.truncate(at);
                out.extend_from_slice(&other[from..]);
            }
            4 => replace_number(rng, &mut out),
            _ => {
                let token = rng.pick(TOKENS).as_bytes();
                out.splice(at..at, token.iter().copied());
            }
        }
    }
    out
}

/// Replaces one number of the text by an extreme one.
fn replace_number(rng: &mut Rng, out: &mut Vec<u8>) {
    let starts: Vec<usize> = (0..out.len())
        .filter(|&i| out[i].is_ascii_digit() && (i == 0 || !out[i - 1].is_ascii_alphanumeric()))
        .collect();
    if starts.is_empty() {
        return;
    }
    let start = *rng.pick(&starts);
    let end = (start..out.len())
        .find(|&i| !(out[i].is_ascii_digit() || matches!(out[i], b'.' | b'e' | b'E' | b'-' | b'+')))
        .unwrap_or(out.len());
    let value = rng.pick(&[
        "0",
        "-1",
        "1e39",
        "NaN",
        "4294967296",
        "1e308",
        "65536",
        "0.000001",
        "3.4e38",
        "1e400",
    ]);
    out.splice(start..end, value.bytes());
}
