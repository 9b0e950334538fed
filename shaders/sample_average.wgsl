// Averages the samples of a multisampled texture: a resolve written as a shader, for the
// `fullscreen` plugin.

@group(0) @binding(0) var samples: texture_multisampled_2d<f32>;

@fragment
fn fs_main(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let texel = vec2<u32>(position.xy);
    let count = textureNumSamples(samples);
    var sum = vec4<f32>(0.0);
    for (var i = 0u; i < count; i++) {
        sum += textureLoad(samples, texel, i);
    }
    return sum / f32(count);
}
