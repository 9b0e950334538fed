// What a sample emits, from the full G-buffer's HDR target (group 1, binding 6): emission,
// an unlit surface's whole color, or the background where nothing was drawn.

@group(1) @binding(6) var hdr_tex: GTexF;

fn emitted(pixel: vec2<i32>, s: u32, g: GSample) -> vec3<f32> {
    return textureLoad(hdr_tex, pixel, s).rgb;
}
