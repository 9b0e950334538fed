// Deferred shading's `shade_sample` for light.wgsl: the lit colour of a G-buffer sample,
// added to the HDR target. Composed after surface.wgsl; `light` is a light's index or
// light.wgsl's ALL_DIRECTIONAL.

// Shades G-buffer sample `s` of `pixel` as the surface point `p` (camera-relative).
fn shade_sample(pixel: vec2<i32>, s: u32, p: vec3<f32>, light: u32) -> SampleLight {
    let none = vec4<f32>(0.0);
    let g = load_gsample(pixel, s);
    if (g.flags & FLAG_LIT) == 0u {
        return SampleLight(none, none);
    }
    let surface = surface_of(g, p);
    var color = vec3<f32>(0.0);
    if light == ALL_DIRECTIONAL {
        // Screen-space AO, when the pass reads it, darkens the ambient term only.
        color = ambient_and_directional(with_screen_ao(surface, pixel));
    } else {
        color = direct_light(surface, lights[light]);
    }
    return SampleLight(vec4<f32>(min(color, vec3<f32>(HALF_MAX)), 0.0), none);
}
