// Reads a multisampled depth buffer's samples into a colour, so that the depth-only pass
// before it has a reader (and a "color" for rgraph bench).

@group(0) @binding(0) var depth: texture_depth_multisampled_2d;

@fragment
fn fs_main(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let texel = vec2<u32>(position.xy);
    var sum = 0.0;
    for (var i = 0u; i < u32(textureNumSamples(depth)); i++) {
        sum += textureLoad(depth, texel, i);
    }
    return vec4<f32>(vec3<f32>(sum / f32(textureNumSamples(depth))), 1.0);
}
