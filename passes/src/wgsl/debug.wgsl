// Debug views of the G-buffer and the edge stencil, read at sample 0.
// Composed after common.wgsl, scene.wgsl, gbuffer_read.wgsl and brdf.wgsl; the inputs
// are group 1, and only `fs_lights` reads the scene (group 0).

// `depth`: view depth shown as 1 / (1 + depth / DEPTH_SCALE), white near, dark far.
override DEPTH_SCALE: f32 = 10.0;
// `lights`: the light count shown red and above.
override HEAT_MAX: f32 = 16.0;

fn covered(pixel: vec2<i32>) -> bool {
    return textureLoad(view_depth_tex, pixel, 0u).r > 0.0;
}

// As seed 003 shows it: red where lighting runs per sample, blue where once per pixel,
// black without geometry.
@fragment
fn fs_edges(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let pixel = pixel_of(position);
    if (textureLoad(stencil_tex, pixel, 0u).r & 0x80u) != 0u {
        return vec4<f32>(1.0, 0.0, 0.0, 1.0);
    }
    return select(vec4<f32>(0.0, 0.0, 0.0, 1.0), vec4<f32>(0.0, 0.0, 1.0, 1.0), covered(pixel));
}

@fragment
fn fs_albedo(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    return vec4<f32>(textureLoad(albedo_tex, pixel_of(position), 0u).rgb, 1.0);
}

// World-space normals mapped from [-1, 1] to [0, 1].
@fragment
fn fs_normals(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let pixel = pixel_of(position);
    let n = oct_decode(textureLoad(normal_tex, pixel, 0u).xy);
    return select(vec4<f32>(0.0, 0.0, 0.0, 1.0), vec4<f32>(n * 0.5 + 0.5, 1.0), covered(pixel));
}

@fragment
fn fs_depth(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let d = textureLoad(view_depth_tex, pixel_of(position), 0u).r;
    let shade = select(0.0, 1.0 / (1.0 + d / DEPTH_SCALE), d > 0.0);
    return vec4<f32>(vec3<f32>(shade), 1.0);
}

// How many lights reach each lit surface point (directional lights included): what a
// light pass with exact volumes shades there, blue for 1 through red for HEAT_MAX or
// more. Black: no geometry or no light.
@fragment
fn fs_lights(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let pixel = pixel_of(position);
    if (material_flags(pixel, 0u).x & FLAG_LIT) == 0u {
        return vec4<f32>(0.0, 0.0, 0.0, 1.0);
    }
    let depth = textureLoad(view_depth_tex, pixel, 0u).r;
    let p = surface_position(vec2<f32>(pixel) + 0.5, depth);
    var count = 0u;
    for (var i = 0u; i < light_count(); i++) {
        count += u32(reaches(lights[i], p));
    }
    if count == 0u {
        return vec4<f32>(0.0, 0.0, 0.0, 1.0);
    }
    return vec4<f32>(heat(f32(count - 1u) / max(HEAT_MAX - 1.0, 1.0)), 1.0);
}
