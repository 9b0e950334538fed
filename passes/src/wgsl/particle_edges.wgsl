// Edge detection on the off-screen particles (seed 001 §23.6.1): a Sobel filter over the
// particle colour, the transmittance (alpha) and the emissive particles, each brought to
// 0..1 (x / (1 + x) for HDR colour), at the off-screen size. An edge (1) is where any
// of the three gradients' magnitude exceeds THRESHOLD; the mixed-resolution composite
// leaves those areas to the full-resolution pass. Composed after common.wgsl; inputs in
// group 1.

@group(1) @binding(0) var particle_color: texture_2d<f32>;
@group(1) @binding(1) var particle_additive: texture_2d<f32>;

override THRESHOLD: f32 = 1.0;

fn signal(pixel: vec2<i32>) -> vec3<f32> {
    let at = clamp(pixel, vec2<i32>(0), vec2<i32>(textureDimensions(particle_color)) - 1);
    let color = textureLoad(particle_color, at, 0);
    let added = luminance(textureLoad(particle_additive, at, 0).rgb);
    let shade = luminance(color.rgb);
    return vec3<f32>(shade / (1.0 + shade), color.a, added / (1.0 + added));
}

@fragment
fn fs_sobel(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let p = pixel_of(position);
    var s: array<vec3<f32>, 9>;
    for (var k = 0; k < 9; k++) {
        s[k] = signal(p + vec2<i32>(k % 3 - 1, k / 3 - 1));
    }
    let gx = (s[2] + 2.0 * s[5] + s[8]) - (s[0] + 2.0 * s[3] + s[6]);
    let gy = (s[6] + 2.0 * s[7] + s[8]) - (s[0] + 2.0 * s[1] + s[2]);
    let magnitude = sqrt(gx * gx + gy * gy);
    let edge = max(max(magnitude.x, magnitude.y), magnitude.z) > THRESHOLD;
    return vec4<f32>(select(0.0, 1.0, edge), 0.0, 0.0, 0.0);
}
