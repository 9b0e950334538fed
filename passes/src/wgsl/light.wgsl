// The light passes: additive accumulation of every light's contribution into a
// multisampled target, shaded once per pixel (non-edge pixels, from sample 0) or once per
// sample (edge pixels). Directional lights and ambient are one full-screen draw; each
// point or spot light is a draw of its volume with instance index = light index.
// Composed after common.wgsl, scene.wgsl, gbuffer_read.wgsl, brdf.wgsl, lighting.wgsl,
// surface.wgsl and what one sample accumulates, `shade_sample(pixel, s, p, light)`: the
// lit colour (light_shade.wgsl, into the HDR target, then common/ao.rs's generated
// `with_screen_ao`) or the light pre-pass's light (light_prepass.wgsl, into the light
// buffer, and its layers' lobes into a second one), and before the generated `LightOut`
// and `light_out` (passes/light.rs), which keep the targets the pass writes.

// What one sample adds to the pass's targets: the lit colour or the light, and the light
// pre-pass's layer lobes (zero where the pass has no target for them).
struct SampleLight {
    light: vec4<f32>,
    lobes: vec4<f32>,
}

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

// A point or spot light drawn full screen instead of as its volume (`volumes: false`):
// the exact reference the volumes must match.
@vertex
fn vs_fullscreen_light(@builtin(vertex_index) index: u32, @builtin(instance_index) light: u32) -> LightVaryings {
    return LightVaryings(fullscreen_position(index, FAR_DEPTH), light);
}

@vertex
fn vs_volume(@location(0) position: vec3<f32>, @builtin(instance_index) light: u32) -> LightVaryings {
    let world = lights[light].volume * vec4<f32>(position, 1.0);
    return LightVaryings(camera.view_proj * world, light);
}

@fragment
fn fs_pixel(in: LightVaryings) -> LightOut {
    let pixel = pixel_of(in.clip);
    return light_out(shade_sample(pixel, 0u, center_surface(pixel, 0u), in.light));
}

// `light_nonedge` with `samples: average`: Killzone 2's on-the-fly resolve (seed 004).
// Every sample of the pixel is shaded and the average written once, to the samples the
// draw covers; samples of no surface (or one the light misses) count as black, so edge
// pixels darken. A baseline to measure, not a way to shade.
@fragment
fn fs_pixel_average(in: LightVaryings) -> LightOut {
    let pixel = pixel_of(in.clip);
    var sum = SampleLight(vec4<f32>(0.0), vec4<f32>(0.0));
    for (var s = 0u; s < SAMPLES; s++) {
        let shaded = shade_sample(pixel, s, center_surface(pixel, s), in.light);
        sum.light += shaded.light;
        sum.lobes += shaded.lobes;
    }
    let n = f32(SAMPLES);
    return light_out(SampleLight(sum.light / n, sum.lobes / n));
}

// Per-sample shading at the sample's own position and depth (surface.wgsl). Both modes
// take the position from the same table, so they agree bit for bit.
@fragment
fn fs_sample(in: LightVaryings, @builtin(sample_index) s: u32) -> LightOut {
    let pixel = pixel_of(in.clip);
    return light_out(shade_sample(pixel, s, sample_surface(pixel, s), in.light));
}

@fragment
fn fs_one_sample(in: LightVaryings) -> LightOut {
    let pixel = pixel_of(in.clip);
    return light_out(shade_sample(pixel, SAMPLE, sample_surface(pixel, SAMPLE), in.light));
}
