// Definitions every deferred shader shares. Composed after a generated prelude that
// defines `SAMPLES` (the G-buffer sample count), the aliases `GTexF` / `GTexU` / `GTexD`
// (the G-buffer texture types: multisampled when SAMPLES > 1, else plain 2D, all read
// with `textureLoad(t, pixel, sample)`) and `SAMPLE_POSITIONS` (each sample's position within
// its pixel), and before the pass's own source.

// The material target's blue channel holds these flags (times 1/255).
const FLAG_LIT: u32 = 1u;     // a surface the light passes shade
const FLAG_UNLIT: u32 = 2u;   // a surface whose color is in the HDR target already
// Its alpha channel holds per-sample edge evidence the G-buffer pass found (times 1/255).
const EDGE_CENTROID: u32 = 0x80u;  // the centroid differed from the pixel center
const EDGE_COVERAGE: u32 = 0x40u;  // the fragment covered only some samples

// The largest finite rgba16float value: light passes never write more, so the HDR
// target holds no Inf from a single contribution.
const HALF_MAX: f32 = 65504.0;
const PI: f32 = 3.14159265358979;

fn unorm8(v: f32) -> u32 {
    return u32(round(clamp(v, 0.0, 1.0) * 255.0));
}

// Octahedral normal encoding into [-1, 1]^2 (rg16float keeps ~0.05 degree precision).
fn oct_wrap(v: vec2<f32>) -> vec2<f32> {
    let sign = select(vec2<f32>(-1.0), vec2<f32>(1.0), v >= vec2<f32>(0.0));
    return (1.0 - abs(v.yx)) * sign;
}

fn oct_encode(n: vec3<f32>) -> vec2<f32> {
    let m = n / max(abs(n.x) + abs(n.y) + abs(n.z), 1e-20);
    return select(oct_wrap(m.xy), m.xy, m.z >= 0.0);
}

fn oct_decode(e: vec2<f32>) -> vec3<f32> {
    var n = vec3<f32>(e, 1.0 - abs(e.x) - abs(e.y));
    let t = max(-n.z, 0.0);
    n.x += select(t, -t, n.x >= 0.0);
    n.y += select(t, -t, n.y >= 0.0);
    // |n| >= 1/sqrt(3) by construction, so this never divides by zero.
    return normalize(n);
}

// A unit vector along `v`, or zero for a zero vector (never NaN).
fn safe_normalize(v: vec3<f32>) -> vec3<f32> {
    return v * inverseSqrt(max(dot(v, v), 1e-20));
}

fn luminance(c: vec3<f32>) -> f32 {
    return dot(c, vec3<f32>(0.2126, 0.7152, 0.0722));
}

// The integer pixel of a fragment position (per-sample positions included).
fn pixel_of(position: vec4<f32>) -> vec2<i32> {
    return vec2<i32>(floor(position.xy));
}

// Where sample `s` of `pixel` lies, in pixel coordinates.
fn sample_position(pixel: vec2<i32>, s: u32) -> vec2<f32> {
    var positions = SAMPLE_POSITIONS;
    return vec2<f32>(pixel) + positions[min(s, SAMPLES - 1u)];
}

// One triangle covering the target, for full-screen passes.
struct Fullscreen {
    @builtin(position) position: vec4<f32>,
}

fn fullscreen_position(index: u32, depth: f32) -> vec4<f32> {
    let uv = vec2<f32>(f32((index << 1u) & 2u), f32(index & 2u));
    return vec4<f32>(uv * 2.0 - 1.0, depth, 1.0);
}

@vertex
fn vs_fullscreen(@builtin(vertex_index) index: u32) -> Fullscreen {
    return Fullscreen(fullscreen_position(index, 0.0));
}
