//! Extreme case 4 (issue 6), normals, the CPU half: the G-buffer's octahedral normal
//! encoding (src/wgsl/common.wgsl's `oct_encode` / `oct_decode`, stored in rg16float)
//! mirrored in Rust, with the half-float rounding of the render target.
//!
//! - Extreme: every direction of a dense sphere (2,000,000 Fibonacci points plus the axes,
//!   the octant edges and directions a hair above and below the equator where the
//!   encoding folds), and zero-length and denormal inputs.
//! - Expected: decoding what was stored gives a unit vector within a fraction of a degree
//!   of the input; degenerate inputs decode to a finite unit vector.
//! - Bound asserted: worst angular error under 0.051 degrees (measured 0.0505), the same
//!   whether the device rounds to half floats to nearest-even or toward zero: the encoder
//!   picks half floats itself (before it did, rounding gave 0.059 and 0.118 degrees);
//!   |decoded| within 1e-6 of 1; every encoding exactly a pair of half floats.
//!
//! The mirror is only as good as its match with the shader: the first test checks that
//! common.wgsl still holds the code mirrored here, character for character.

use std::f64::consts::PI;

/// The WGSL the functions below mirror.
const MIRRORED_WGSL: &str = r#"fn oct_wrap(v: vec2<f32>) -> vec2<f32> {
    let sign = select(vec2<f32>(-1.0), vec2<f32>(1.0), v >= vec2<f32>(0.0));
    return (1.0 - abs(v.yx)) * sign;
}

fn oct_encode_exact(n: vec3<f32>) -> vec2<f32> {
    let m = n / max(abs(n.x) + abs(n.y) + abs(n.z), 1e-20);
    return select(oct_wrap(m.xy), m.xy, m.z >= 0.0);
}

// The spacing of half floats at `x` (|x| <= 1: 2^-24 for subnormals), a power of two made
// from its bits (exp2 and division need not be exact).
fn half_step_exponent(x: f32) -> i32 {
    let exponent = i32((bitcast<u32>(x) >> 23u) & 0xffu) - 127;
    return max(exponent, -14) - 10;
}

// The largest half float <= x, and the spacing to the next one (|x| <= 1).
fn half_floor(x: f32) -> vec2<f32> {
    let e = half_step_exponent(x);
    let step = bitcast<f32>(u32(e + 127) << 23u);
    let inverse = bitcast<f32>(u32(127 - e) << 23u);
    return vec2<f32>(floor(x * inverse) * step, step);
}

fn oct_encode(n: vec3<f32>) -> vec2<f32> {
    let e = oct_encode_exact(n);
    let x = half_floor(e.x);
    let y = half_floor(e.y);
    var best = vec2<f32>(x.x, y.x);
    var best_dot = dot(oct_decode(best), n);
    for (var i = 1u; i < 4u; i++) {
        let c = vec2<f32>(x.x + f32(i & 1u) * x.y, y.x + f32(i >> 1u) * y.y);
        let d = dot(oct_decode(c), n);
        if d > best_dot {
            best = c;
            best_dot = d;
        }
    }
    return best;
}

fn oct_decode(e: vec2<f32>) -> vec3<f32> {
    var n = vec3<f32>(e, 1.0 - abs(e.x) - abs(e.y));
    let t = max(-n.z, 0.0);
    n.x += select(t, -t, n.x >= 0.0);
    n.y += select(t, -t, n.y >= 0.0);
    // |n| >= 1/sqrt(3) by construction, so this never divides by zero.
    return normalize(n);
}"#;

/// The G-buffer pass makes the interpolated normal a unit vector first.
const MIRRORED_NORMALIZE: &str = r#"fn safe_normalize(v: vec3<f32>) -> vec3<f32> {
    return v * inverseSqrt(max(dot(v, v), 1e-20));
}"#;

const MIRRORED_UNIT_NORMAL: &str = r#"fn unit_normal(v: vec3<f32>) -> vec3<f32> {
    let a = abs(v);
    let largest = max(max(a.x, a.y), a.z);
    return safe_normalize(select(v / largest, vec3<f32>(0.0), largest == 0.0));
}"#;

/// The worst angular error allowed, in degrees.
const MAX_ERROR_DEGREES: f64 = 0.051;

fn sign(v: f32) -> f32 {
    if v >= 0.0 {
        1.0
    } else {
        -1.0
    }
}

fn safe_normalize(v: [f32; 3]) -> [f32; 3] {
    let d = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).max(1e-20);
    let s = 1.0 / d.sqrt();
    v.map(|c| c * s)
}

fn unit_normal(v: [f32; 3]) -> [f32; 3] {
    let largest = v[0].abs().max(v[1].abs()).max(v[2].abs());
    if largest == 0.0 {
        safe_normalize([0.0; 3])
    } else {
        safe_normalize(v.map(|c| c / largest))
    }
}

fn oct_encode_exact(n: [f32; 3]) -> [f32; 2] {
    let l1 = (n[0].abs() + n[1].abs() + n[2].abs()).max(1e-20);
    let m = n.map(|c| c / l1);
    if m[2] >= 0.0 {
        [m[0], m[1]]
    } else {
        [
            (1.0 - m[1].abs()) * sign(m[0]),
            (1.0 - m[0].abs()) * sign(m[1]),
        ]
    }
}

fn half_step_exponent(x: f32) -> i32 {
    let exponent = ((x.to_bits() >> 23) & 0xff) as i32 - 127;
    exponent.max(-14) - 10
}

fn half_floor(x: f32) -> [f32; 2] {
    let e = half_step_exponent(x);
    let step = f32::from_bits(((e + 127) as u32) << 23);
    let inverse = f32::from_bits(((127 - e) as u32) << 23);
    [(x * inverse).floor() * step, step]
}

fn dot(a: [f32; 3], b: [f32; 3]) -> f32 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn oct_encode(n: [f32; 3]) -> [f32; 2] {
    let e = oct_encode_exact(n);
    let (x, y) = (half_floor(e[0]), half_floor(e[1]));
    let mut best = [x[0], y[0]];
    let mut best_dot = dot(oct_decode(best), n);
    for i in 1..4u32 {
        let c = [x[0] + (i & 1) as f32 * x[1], y[0] + (i >> 1) as f32 * y[1]];
        let d = dot(oct_decode(c), n);
        if d > best_dot {
            (best, best_dot) = (c, d);
        }
    }
    best
}

fn oct_decode(e: [f32; 2]) -> [f32; 3] {
    let mut n = [e[0], e[1], 1.0 - e[0].abs() - e[1].abs()];
    let t = (-n[2]).max(0.0);
    n[0] += if n[0] >= 0.0 { -t } else { t };
    n[1] += if n[1] >= 0.0 { -t } else { t };
    let length = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    n.map(|c| c / length)
}

/// How the render target rounds an f32 to a half float.
#[derive(Copy, Clone, Debug)]
enum Rounding {
    NearestEven,
    TowardZero,
}

/// `x` rounded to the nearest half float (|x| <= 1 here: no overflow), as f32.
fn to_half(x: f32, rounding: Rounding) -> f32 {
    let exponent = ((x.to_bits() >> 23) & 0xff) as i32 - 127;
    // Normal halves have 10 mantissa bits; below 2^-14 the step is 2^-24 (subnormals).
    let step = 2f32.powi(exponent.max(-14) - 10);
    let scaled = x / step;
    let rounded = match rounding {
        Rounding::NearestEven => scaled.round_ties_even(),
        Rounding::TowardZero => scaled.trunc(),
    };
    rounded * step
}

/// What the G-buffer stores for `n` and the light passes read back, through a render
/// target that rounds as `rounding` says.
fn stored(n: [f32; 3], rounding: Rounding) -> [f32; 3] {
    let e = oct_encode(unit_normal(n));
    let half = e.map(|c| to_half(c, rounding));
    assert_eq!(e, half, "oct_encode returned {e:?}, not half floats");
    oct_decode(half)
}

/// The angle between two directions, in degrees (atan2 form: exact for tiny angles).
fn angle_degrees(a: [f32; 3], b: [f64; 3]) -> f64 {
    let a = a.map(f64::from);
    let cross = [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ];
    let sin = (cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2]).sqrt();
    let cos = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    sin.atan2(cos).to_degrees()
}

/// The dense sphere: Fibonacci points, the axes, octant edges and the fold.
fn directions() -> Vec<[f64; 3]> {
    const N: usize = 2_000_000;
    let golden = PI * (3.0 - 5f64.sqrt());
    let mut all: Vec<[f64; 3]> = (0..N)
        .map(|i| {
            let z = 1.0 - 2.0 * (i as f64 + 0.5) / N as f64;
            let r = (1.0 - z * z).sqrt();
            let phi = golden * i as f64;
            [r * phi.cos(), r * phi.sin(), z]
        })
        .collect();
    for k in 0..3600 {
        let phi = f64::from(k) * PI / 1800.0;
        for z in [0.0f64, 1e-7, -1e-7, 1e-3, -1e-3, 0.999_999, -0.999_999] {
            let r = (1.0 - z * z).sqrt();
            all.push([r * phi.cos(), r * phi.sin(), z]);
        }
    }
    for s in [1.0, -1.0] {
        all.extend([[s, 0.0, 0.0], [0.0, s, 0.0], [0.0, 0.0, s]]);
    }
    all
}

#[test]
fn the_mirror_matches_common_wgsl() {
    let wgsl = include_str!("../src/wgsl/common.wgsl");
    for code in [MIRRORED_WGSL, MIRRORED_NORMALIZE, MIRRORED_UNIT_NORMAL] {
        assert!(
            wgsl.contains(code),
            "src/wgsl/common.wgsl no longer holds the code this test mirrors; update the \
             Rust mirror and MIRRORED_WGSL together:\n{code}"
        );
    }
}

/// The worst angular error over the dense sphere, for both roundings a device may use.
#[test]
fn octahedral_encoding_worst_angular_error_is_bounded() {
    let directions = directions();
    for rounding in [Rounding::NearestEven, Rounding::TowardZero] {
        let (mut worst, mut at) = (0.0f64, [0.0; 3]);
        let mut worst_length = 0.0f64;
        for &d in &directions {
            let n = d.map(|c| c as f32);
            let decoded = stored(n, rounding);
            assert!(
                decoded.iter().all(|c| c.is_finite()),
                "{d:?} decodes to {decoded:?} ({rounding:?})"
            );
            let length = decoded
                .iter()
                .map(|&c| f64::from(c).powi(2))
                .sum::<f64>()
                .sqrt();
            worst_length = worst_length.max((length - 1.0).abs());
            let error = angle_degrees(decoded, d);
            if error > worst {
                (worst, at) = (error, d);
            }
        }
        println!(
            "{rounding:?}: worst angular error {worst:.5} degrees at {at:?} over {} \
             directions; worst |length - 1| {worst_length:.2e}",
            directions.len()
        );
        assert!(
            worst < MAX_ERROR_DEGREES,
            "{rounding:?}: the octahedral rg16float encoding is off by {worst} degrees at \
             {at:?} (bound {MAX_ERROR_DEGREES})"
        );
        assert!(
            worst_length < 1e-6,
            "{rounding:?}: |n| off 1 by {worst_length}"
        );
    }
}

/// Zero-length, denormal and enormous normals (what a damaged or quantized mesh may
/// hold) encode and decode to finite unit vectors; non-degenerate ones keep their
/// direction within the bound above.
#[test]
fn degenerate_normals_decode_to_finite_unit_vectors() {
    let tiny = f32::from_bits(1); // the smallest denormal
    let cases: [([f32; 3], Option<[f64; 3]>); 8] = [
        ([0.0, 0.0, 0.0], None),
        ([-0.0, -0.0, -0.0], None),
        ([tiny, 0.0, 0.0], None),
        ([0.0, -tiny, tiny], None),
        ([1e-38, 0.0, -1e-38], None),
        ([1e-19, 0.0, 0.0], Some([1.0, 0.0, 0.0])),
        ([0.0, 3e38, 0.0], Some([0.0, 1.0, 0.0])),
        ([0.0, 0.0, -1e-12], Some([0.0, 0.0, -1.0])),
    ];
    for (n, direction) in cases {
        for rounding in [Rounding::NearestEven, Rounding::TowardZero] {
            let decoded = stored(n, rounding);
            let length = decoded.iter().map(|&c| c * c).sum::<f32>().sqrt();
            assert!(
                decoded.iter().all(|c| c.is_finite()) && (length - 1.0).abs() < 1e-6,
                "normal {n:?} decodes to {decoded:?} ({rounding:?})"
            );
            if let Some(d) = direction {
                let error = angle_degrees(decoded, d);
                assert!(
                    error < MAX_ERROR_DEGREES,
                    "normal {n:?} decodes to {decoded:?}, {error} degrees off"
                );
            }
        }
    }
}
