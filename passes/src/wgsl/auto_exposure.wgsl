// The auto-exposure pass: meters the resolved HDR image as engines do (a histogram of
// log2 luminance, averaged between two percentiles of the lit pixels) and stores the
// exposure that maps that average to the key (middle grey) in a 1x1 r32float texture the
// tone mapper multiplies by. One workgroup: it meters at most about 2^18 pixels, on a
// grid of every STEP-th pixel in each direction, which is plenty for an average and keeps
// the pass one dispatch with no global atomics. Composed after common.wgsl.

@group(1) @binding(0) var hdr_tex: texture_2d<f32>;
@group(1) @binding(1) var exposure_out: texture_storage_2d<r32float, write>;

// The luminance the average maps to.
override KEY: f32 = 0.18;
// Lit pixels darker than the LOW share and brighter than the HIGH share of them are left
// out of the average: a few highlights or deep shadows do not swing the exposure.
override LOW: f32 = 0.1;
override HIGH: f32 = 0.9;

// Bin 0 holds black pixels (the background clear, unlit geometry): they are not metered.
// Bins 1 to 255 span log2 luminance MIN_LOG2 to MIN_LOG2 + RANGE_LOG2, past the largest
// half float.
const BINS: u32 = 256u;
const MIN_LOG2: f32 = -16.0;
const RANGE_LOG2: f32 = 32.0;
const BLACK: f32 = 1.5258789e-5; // 2^-16
const METERED: f32 = 262144.0;

var<workgroup> bins: array<atomic<u32>, 256>;

fn bin_of(luminance: f32) -> u32 {
    if luminance < BLACK {
        return 0u;
    }
    let t = (log2(luminance) - MIN_LOG2) / RANGE_LOG2;
    return 1u + u32(clamp(t * 254.0, 0.0, 254.0));
}

// The log2 luminance at the middle of bin `b` (b >= 1).
fn log2_of(b: u32) -> f32 {
    return MIN_LOG2 + (f32(b - 1u) + 0.5) / 254.0 * RANGE_LOG2;
}

@compute @workgroup_size(16, 16, 1)
fn cs_auto_exposure(@builtin(local_invocation_index) i: u32) {
    atomicStore(&bins[i], 0u);
    workgroupBarrier();
    let size = textureDimensions(hdr_tex);
    let step = max(1u, u32(ceil(sqrt(f32(size.x) * f32(size.y) / METERED))));
    let columns = (size.x + step - 1u) / step;
    let count = columns * ((size.y + step - 1u) / step);
    for (var k = i; k < count; k += BINS) {
        let pixel = vec2<u32>(k % columns, k / columns) * step;
        // As the tone mapper: an infinite sum counts as the largest half float.
        let c = clamp(textureLoad(hdr_tex, pixel, 0).rgb, vec3<f32>(0.0), vec3<f32>(HALF_MAX));
        atomicAdd(&bins[bin_of(luminance(c))], 1u);
    }
    workgroupBarrier();
    if i != 0u {
        return;
    }
    var lit = 0u;
    for (var b = 1u; b < BINS; b++) {
        lit += atomicLoad(&bins[b]);
    }
    // The mean log2 luminance of the lit pixels ranked between LOW and HIGH: each bin
    // counts with the part of it inside that range.
    let low = f32(lit) * LOW;
    let high = f32(lit) * HIGH;
    var below = 0.0;
    var sum = 0.0;
    var weight = 0.0;
    for (var b = 1u; b < BINS; b++) {
        let n = f32(atomicLoad(&bins[b]));
        let inside = max(min(below + n, high) - max(below, low), 0.0);
        sum += inside * log2_of(b);
        weight += inside;
        below += n;
    }
    // A black frame keeps exposure 1: there is nothing to expose for.
    var exposure = 1.0;
    if weight > 0.0 {
        exposure = clamp(KEY / exp2(sum / weight), 1.0 / 16777216.0, 16777216.0);
    }
    textureStore(exposure_out, vec2<u32>(0u), vec4<f32>(exposure, 0.0, 0.0, 1.0));
}
