// The resolve pass: averages the samples of the HDR target into one pixel.
// Composed after common.wgsl; inputs are group 1, like every deferred pass's.

@group(1) @binding(0) var hdr_tex: GTexF;

// 0: box, the plain average. 1: tonemapped, each sample weighted by 1 / (1 + luminance):
// the average of Reinhard-tonemapped samples, tone mapping undone, so that one very
// bright sample does not wash out an edge pixel (the prior-art note's "known cure").
override MODE: u32 = 0u;
// The exposure the tone mapper applies, so the weights see the same brightness.
override EXPOSURE: f32 = 1.0;

@fragment
fn fs_resolve(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let pixel = pixel_of(position);
    var sum = vec3<f32>(0.0);
    var weights = 0.0;
    for (var s = 0u; s < SAMPLES; s++) {
        // Additive blending can overflow half floats to Inf: clamp what is read.
        let c = clamp(textureLoad(hdr_tex, pixel, s).rgb, vec3<f32>(0.0), vec3<f32>(HALF_MAX));
        let w = select(1.0, 1.0 / (1.0 + EXPOSURE * luminance(c)), MODE == 1u);
        sum += w * c;
        weights += w;
    }
    return vec4<f32>(sum / weights, 1.0);
}
