// The light passes: additive HDR accumulation of every light's contribution into the
// multisampled HDR target, shaded once per pixel (non-edge pixels, from sample 0) or
// once per sample (edge pixels). Directional lights and ambient are one full-screen draw;
// each point or spot light is a draw of its volume with instance index = light index.
// Composed after common.wgsl, scene.wgsl, gbuffer_read.wgsl and brdf.wgsl.

// Clip depth of the far plane: 0 with reversed Z, 1 without.
override FAR_DEPTH: f32 = 0.0;
// `fs_one_sample`: the sample this pipeline shades (its multisample mask is 1 << SAMPLE).
override SAMPLE: u32 = 0u;

// `light` for the full-screen draw: all directional lights plus ambient.
const ALL_DIRECTIONAL: u32 = 0xffffffffu;

struct LightVaryings {
    @builtin(position) clip: vec4<f32>,
    @location(0) @interpolate(flat) light: u32,
}

// Drawn at the far plane with a depth test that passes only in front of it: pixels
// without geometry are never shaded.
@vertex
fn vs_directional(@builtin(vertex_index) index: u32) -> LightVaryings {
    return LightVaryings(fullscreen_position(index, FAR_DEPTH), ALL_DIRECTIONAL);
}

@vertex
fn vs_volume(@location(0) position: vec3<f32>, @builtin(instance_index) light: u32) -> LightVaryings {
    let world = lights[light].volume * vec4<f32>(position, 1.0);
    return LightVaryings(camera.view_proj * world, light);
}

fn shade_sample(pixel: vec2<i32>, s: u32, light: u32) -> vec4<f32> {
    let g = load_gsample(pixel, s);
    if (g.flags & FLAG_LIT) == 0u {
        return vec4<f32>(0.0);
    }
    // The pixel center, not the sample position, for every shading frequency: the
    // per-sample modes then give bit-identical results.
    let p = surface_position(vec2<f32>(pixel) + 0.5, g.view_depth);
    let surface = Surface(p, g.normal, safe_normalize(-p), g.albedo, g.metallic, g.roughness);
    var color = vec3<f32>(0.0);
    if light == ALL_DIRECTIONAL {
        color = light_info.ambient * g.albedo;
        for (var i = 0u; i < light_info.directional_count; i++) {
            color += shade_light(surface, lights[i]);
        }
    } else {
        color = shade_light(surface, lights[light]);
    }
    return vec4<f32>(min(color, vec3<f32>(HALF_MAX)), 0.0);
}

@fragment
fn fs_pixel(in: LightVaryings) -> @location(0) vec4<f32> {
    return shade_sample(pixel_of(in.clip), 0u, in.light);
}

@fragment
fn fs_sample(in: LightVaryings, @builtin(sample_index) s: u32) -> @location(0) vec4<f32> {
    return shade_sample(pixel_of(in.clip), s, in.light);
}

@fragment
fn fs_one_sample(in: LightVaryings) -> @location(0) vec4<f32> {
    return shade_sample(pixel_of(in.clip), SAMPLE, in.light);
}
