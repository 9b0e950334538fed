// The particle composite (seed 001): the off-screen particle targets, upsampled
// bilinearly onto the output-sized HDR image. `color` holds the blended particles over
// black in rgb and their transmittance in alpha, `additive` the emissive ones; the
// pipeline blends with source factor one and destination factor source alpha, so the
// image becomes hdr * T + C + A. Composed after common.wgsl and scene.wgsl (the camera's
// viewport is the output size); inputs in group 1.

@group(1) @binding(0) var particle_color: texture_2d<f32>;
@group(1) @binding(1) var particle_additive: texture_2d<f32>;
// particle_edges' mask, at the off-screen size (mixed resolution only).
@group(1) @binding(2) var particle_edges: texture_2d<f32>;

// The four off-screen texels around an output pixel and their bilinear weights. At equal
// sizes the ratio is exactly 1, so the first texel is the pixel's own with weight 1.
struct Bilinear {
    texels: array<vec2<i32>, 4>,
    weights: vec4<f32>,
}

fn bilinear(position: vec4<f32>) -> Bilinear {
    let size = textureDimensions(particle_color);
    let at = position.xy * (vec2<f32>(size) / camera.viewport) - 0.5;
    let base = floor(at);
    let f = at - base;
    let last = vec2<i32>(size) - 1;
    let lo = clamp(vec2<i32>(base), vec2<i32>(0), last);
    let hi = clamp(vec2<i32>(base) + 1, vec2<i32>(0), last);
    return Bilinear(
        array<vec2<i32>, 4>(lo, vec2<i32>(hi.x, lo.y), vec2<i32>(lo.x, hi.y), hi),
        vec4<f32>((1.0 - f.x) * (1.0 - f.y), f.x * (1.0 - f.y), (1.0 - f.x) * f.y, f.x * f.y),
    );
}

fn composite(taps: Bilinear) -> vec4<f32> {
    var color = vec4<f32>(0.0);
    var added = vec3<f32>(0.0);
    for (var i = 0u; i < 4u; i++) {
        color += taps.weights[i] * textureLoad(particle_color, taps.texels[i], 0);
        added += taps.weights[i] * textureLoad(particle_additive, taps.texels[i], 0).rgb;
    }
    return vec4<f32>(min(color.rgb + added, vec3<f32>(HALF_MAX)), color.a);
}

@fragment
fn fs_composite_particles(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    return composite(bilinear(position));
}

// Mixed resolution: no output, and so no stencil mark, where any texel the pixel
// interpolates is an edge (a blocky area, left to the full-resolution pass).
@fragment
fn fs_composite_particles_masked(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let taps = bilinear(position);
    for (var i = 0u; i < 4u; i++) {
        if textureLoad(particle_edges, taps.texels[i], 0).r > 0.5 {
            discard;
        }
    }
    return composite(taps);
}

// In compute (`stage: compute`): the same blend over the image `under`, stored into a new
// one: `under * T + C + A`, its alpha (a background's transmittance) times T, as the
// fragment composite's blend state computes it.
@group(1) @binding(3) var under_tex: texture_2d<f32>;
@group(1) @binding(4) var out_tex: texture_storage_2d<rgba16float, write>;

@compute @workgroup_size(8, 8)
fn cs_composite_particles(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= textureDimensions(out_tex)) {
        return;
    }
    let particles = composite(bilinear(vec4<f32>(vec2<f32>(id.xy) + 0.5, 0.0, 1.0)));
    let under = textureLoad(under_tex, vec2<i32>(id.xy), 0);
    textureStore(out_tex, id.xy, vec4<f32>(under.rgb * particles.a + particles.rgb, under.a * particles.a));
}
