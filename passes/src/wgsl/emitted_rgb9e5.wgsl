// What a sample emits, from the lean G-buffer's emission channel (group 1, binding 6,
// RGB9E5 in rg16uint, low half in red, cleared to the background) plus an unlit surface's color, which the
// lean G-buffer keeps in albedo.

@group(1) @binding(6) var emission_tex: GTexU;

fn emitted(pixel: vec2<i32>, s: u32, g: GSample) -> vec3<f32> {
    let halves = textureLoad(emission_tex, pixel, s);
    let emission = unpack_rgb9e5(halves.r | (halves.g << 16u));
    return select(emission, emission + g.albedo, (g.flags & FLAG_UNLIT) != 0u);
}
