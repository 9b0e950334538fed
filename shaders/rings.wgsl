// Concentric rings shaded once per sample (reading `sample_index` makes the fragment stage
// run per sample, so `position` is each sample's own), for the `fullscreen` plugin.

@fragment
fn fs_main(
    @builtin(position) position: vec4<f32>,
    @builtin(sample_index) sample: u32,
) -> @location(0) vec4<f32> {
    let d = length(position.xy - vec2<f32>(64.0, 64.0));
    let ring = step(0.5, fract(d / 6.0));
    // `sample` is read only to request per-sample shading.
    _ = sample;
    return vec4<f32>(ring * 0.8, ring * 0.6, ring * 0.2, 0.0);
}
