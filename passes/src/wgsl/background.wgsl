// The background (passes/background.rs): where the opaque passes drew nothing, the
// environment's radiance seen through the pixel, added to the resolved HDR image in
// proportion to the pixel's samples that show nothing, and that share itself in alpha
// (the background's transmittance, which the transparent and particle composites then
// multiply and tone mapping reads for a colour or transparent background). Composed
// after common.wgsl and scene.wgsl, then common/opaque_depth.rs's block reading the
// opaque passes' depth or a compute rasteriser's keys (group 1): `sample_depth_at`,
// `one_surface` and `coverage_size`, the pixels those cover (the image's).

// Whether sample `s` of `pixel` shows a surface: its depth is not the far depth the
// buffer was cleared to (the keys' 0 with reversed-Z).
fn drawn(pixel: vec2<i32>, s: u32) -> bool {
    return sample_depth_at(pixel, s) != FAR_DEPTH;
}

// Add the environment's radiance (1), or nothing and leave the background to tone
// mapping (0: a colour, or transparency).
override ENVIRONMENT_BACKGROUND: bool = true;

// The share of `pixel`'s samples that show nothing.
fn uncovered(pixel: vec2<i32>) -> f32 {
    if one_surface(pixel) {
        return f32(!drawn(pixel, 0u));
    }
    var empty = 0u;
    for (var s = 0u; s < SAMPLES; s++) {
        empty += u32(!drawn(pixel, s));
    }
    return f32(empty) / f32(SAMPLES);
}

// The environment's radiance arriving through pixel coordinate `at` of the image: its
// cube map's level 0, which mirror reflections read too. The image may be larger than
// the output the camera's viewport counts (a supersampled reference's).
fn environment_seen(at: vec2<f32>) -> vec3<f32> {
    let output = at * camera.viewport / coverage_size();
    // Two points on the pixel's ray; which of the two clip depths is nearer depends on the
    // depth convention, so the ray is turned to point away from the camera.
    let along = unproject(output, 0.25) - unproject(output, 0.5);
    let ray = select(-along, along, dot(along, camera.forward) > 0.0);
    let radiance = textureSampleLevel(environment_tex, environment_sampler, ray, 0.0).rgb;
    return min(radiance * light_info.environment_intensity, vec3<f32>(HALF_MAX));
}

// Blended with source factor one and destination one (alpha: one and zero): the image
// gains t * environment, and its alpha becomes t.
@fragment
fn fs_background(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let t = uncovered(pixel_of(position));
    var light = vec3<f32>(0.0);
    if ENVIRONMENT_BACKGROUND && t > 0.0 {
        light = t * environment_seen(position.xy);
    }
    return vec4<f32>(light, t);
}
