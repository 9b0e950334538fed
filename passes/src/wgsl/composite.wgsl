// The transparent composite: the accumulation target of the transparent pass (colour
// over black in rgb, transmittance in alpha, per sample) onto the single-sampled HDR
// image. The pipeline blends with source factor one and destination factor source alpha,
// so the target becomes hdr * T + C. Composed after common.wgsl; input in group 1.

@group(1) @binding(0) var accum_tex: GTexF;

// The mean colour C and mean transmittance T of the pixel's samples.
@fragment
fn fs_composite(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let pixel = pixel_of(position);
    var sum = vec4<f32>(0.0);
    for (var s = 0u; s < SAMPLES; s++) {
        sum += textureLoad(accum_tex, pixel, s);
    }
    let mean = sum / f32(SAMPLES);
    return vec4<f32>(min(mean.rgb, vec3<f32>(HALF_MAX)), mean.a);
}
