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

// RGB9E5, the shared-exponent HDR encoding of EXT_texture_shared_exponent: three 9-bit
// mantissas and a 5-bit exponent in 32 bits, so the lean G-buffer's emission costs 4
// bytes per sample where an rgba16float target costs 8. Each channel's error is below
// 2^-9 of the brightest channel (or 2^-25). (No GPU renders to rgb9e5ufloat, hence
// a uint target.)
const RGB9E5_MAX: f32 = 65408.0;  // (2^9 - 1) / 2^9 * 2^16

fn pack_rgb9e5(rgb: vec3<f32>) -> u32 {
    let c = clamp(rgb, vec3<f32>(0.0), vec3<f32>(RGB9E5_MAX));
    let brightest = max(c.r, max(c.g, c.b));
    if !(brightest > 0.0) {
        return 0u;
    }
    // frexp gives floor(log2(brightest)) + 1 exactly; log2 may round up at powers of two.
    var e = max(frexp(brightest).exp, -15) + 15;
    if u32(floor(brightest * exp2(f32(24 - e)) + 0.5)) == 512u {
        e += 1;
    }
    let m = vec3<u32>(floor(c * exp2(f32(24 - e)) + 0.5));
    return m.r | (m.g << 9u) | (m.b << 18u) | (u32(e) << 27u);
}

fn unpack_rgb9e5(bits: u32) -> vec3<f32> {
    let m = vec3<u32>(bits & 511u, (bits >> 9u) & 511u, (bits >> 18u) & 511u);
    return vec3<f32>(m) * exp2(f32(bits >> 27u) - 24.0);
}

// Octahedral normal encoding into [-1, 1]^2, stored in rg16float. `oct_encode` returns
// half floats (exact in f32, so the target stores them unchanged whatever its rounding):
// of the four around the exact encoding, the pair that decodes closest to `n` (Cigolle et
// al. 2014's "precise" variant). Worst error 0.0505 degrees, where rounding each
// coordinate to nearest gives 0.059 and toward zero 0.118
// (passes/tests/extremes_normals.rs).
fn oct_wrap(v: vec2<f32>) -> vec2<f32> {
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
}

// A unit vector along `v`, or zero for a zero vector (never NaN).
fn safe_normalize(v: vec3<f32>) -> vec3<f32> {
    return v * inverseSqrt(max(dot(v, v), 1e-20));
}

// A unit normal along `v` for any finite `v`: scaled by its largest component first, so
// denormal and huge vectors keep their direction (the dot product neither underflows nor
// overflows); zero (or a denormal a device flushes) gives zero.
fn unit_normal(v: vec3<f32>) -> vec3<f32> {
    let a = abs(v);
    let largest = max(max(a.x, a.y), a.z);
    return safe_normalize(select(v / largest, vec3<f32>(0.0), largest == 0.0));
}

// The normal to shade with where a mesh gave its vertices none (scene::Vertex: a zero
// normal asks for the triangle's face normal, glTF's "flat normals", so that such a mesh
// keeps its shared, indexed vertices rather than three of its own per triangle).
// `interpolated` is the vertices' normal at the fragment (zero only where all three are)
// and `winding` the triangle's counter-clockwise normal, of any length.
fn normal_or_face(interpolated: vec3<f32>, winding: vec3<f32>) -> vec3<f32> {
    return select(interpolated, winding, all(interpolated == vec3<f32>(0.0)));
}

// A fragment's counter-clockwise normal from the derivatives of its position `p`: the
// screen's x runs right and y down, so dp/dy x dp/dx points at the camera whichever way the
// triangle winds, and a front face's winding normal is that one, a back face's the other.
fn winding_normal(p: vec3<f32>, front: bool) -> vec3<f32> {
    let at_camera = cross(dpdy(p), dpdx(p));
    return select(-at_camera, at_camera, front);
}

// A heat-map colour for `t` in [0, 1]: blue through cyan, green and yellow to red.
fn heat(t: f32) -> vec3<f32> {
    let x = clamp(t, 0.0, 1.0) * 4.0;
    return clamp(vec3<f32>(x - 2.0, min(x, 4.0 - x), 2.0 - x), vec3<f32>(0.0), vec3<f32>(1.0));
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

// Clip depth of the far plane, the value a depth buffer is cleared to: 0 with reversed
// Z, 1 without (the pass gives it).
override FAR_DEPTH: f32 = 0.0;

// The full-screen triangle at the far depth: common/background.rs's fill.
@vertex
fn vs_fullscreen_far(@builtin(vertex_index) index: u32) -> Fullscreen {
    return Fullscreen(fullscreen_position(index, FAR_DEPTH));
}

// Which material layers the scene has (variant.rs; the defaults are the general shader):
// KHR_materials_ior and _specular (a dielectric F0 or specular weight other than the core
// model's), _clearcoat and _sheen. Without one its code is compiled out: plain_layers()
// are what a material without the extension has, and the gated code would change nothing.
// A G-buffer holds a layer only where its plan keeps the layer's target
// (gbuffer_layers.wgsl); elsewhere its samples' layers are plain_layers().
override SPECULAR: bool = true;
override CLEARCOAT: bool = true;
override SHEEN: bool = true;

// What KHR_materials_ior, _specular, _clearcoat and _sheen add to a surface point
// (material.wgsl computes them, brdf.wgsl shades them).
struct Layers {
    // The dielectric reflectance at normal incidence, ((ior - 1) / (ior + 1))^2 times the
    // specular colour, at most 1; and the specular weight that scales it and the grazing
    // reflectance (KHR_materials_specular's specularFactor).
    specular_f0: vec3<f32>,
    specular: f32,
    // The clear coat's strength, perceptual roughness and unit world-space normal
    // (tangent-space in a MaterialSample, material.wgsl's surface_layers).
    clearcoat: f32,
    clearcoat_roughness: f32,
    clearcoat_normal: vec3<f32>,
    // The sheen's linear colour (black: none) and perceptual roughness.
    sheen_color: vec3<f32>,
    sheen_roughness: f32,
}

// The core metallic-roughness model's: F0 0.04 (ior 1.5), weight 1, no coat, no sheen.
fn plain_layers() -> Layers {
    return Layers(vec3<f32>(0.04), 1.0, 0.0, 0.0, vec3<f32>(0.0, 0.0, 1.0), vec3<f32>(0.0), 0.0);
}

// A sample's surface as the light passes read it: from a G-buffer (gbuffer_read.wgsl) or
// rebuilt from a visibility buffer (visibility_read.wgsl).
struct GSample {
    albedo: vec3<f32>,
    // Ambient occlusion (albedo's alpha): scales ambient light only.
    occlusion: f32,
    normal: vec3<f32>,
    metallic: f32,
    roughness: f32,
    flags: u32,
    edge_bits: u32,
    // 0 where no geometry was drawn.
    view_depth: f32,
    // What a visibility buffer rebuilds beside the material: the triangle's ID + 1 and
    // the emission. A G-buffer's samples leave both 0 (its emission is a channel of its
    // own: emitted_*.wgsl).
    id: u32,
    emission: vec3<f32>,
    // A G-buffer's samples: the layers it holds (gbuffer_read.wgsl's load_layers), the
    // core model's elsewhere.
    layers: Layers,
}
