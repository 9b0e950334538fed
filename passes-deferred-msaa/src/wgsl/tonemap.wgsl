// The tone-mapping pass: exposure, then an operator, into an sRGB target (the format
// encodes; the shader writes linear values in [0, 1]). Composed after common.wgsl and
// scene.wgsl; inputs are group 1, like every deferred pass's. The fs_*_frame entry points
// read group 0 (a host's scene) for the frame's exposure factor, a uniform, so a new
// exposure each frame builds no pipeline; the others (no host) use EXPOSURE alone.

@group(1) @binding(0) var hdr_tex: texture_2d<f32>;
// fs_tonemap_metered's: the exposure auto_exposure.wgsl metered, at texel (0, 0).
@group(1) @binding(1) var exposure_tex: texture_2d<f32>;

// 0: none (clamp), 1: Reinhard per channel, 2: ACES filmic (Narkowicz's fit).
override OPERATOR: u32 = 0u;
override EXPOSURE: f32 = 1.0;

fn aces(x: vec3<f32>) -> vec3<f32> {
    return (x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14);
}

fn tonemap(position: vec4<f32>, exposure: f32) -> vec4<f32> {
    // An additive blend past the half-float range may store infinity (devices differ:
    // lavapipe saturates); clamped first, it maps to white instead of inf / inf = NaN.
    let texel = textureLoad(hdr_tex, pixel_of(position), 0).rgb;
    let stored = clamp(texel, vec3<f32>(0.0), vec3<f32>(HALF_MAX));
    let c = stored * exposure;
    var mapped = c;
    if OPERATOR == 1u {
        mapped = c / (1.0 + c);
    } else if OPERATOR == 2u {
        mapped = aces(c);
    }
    return vec4<f32>(clamp(mapped, vec3<f32>(0.0), vec3<f32>(1.0)), 1.0);
}

@fragment
fn fs_tonemap(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    return tonemap(position, EXPOSURE);
}

// Auto exposure: the metered exposure, times EXPOSURE.
@fragment
fn fs_tonemap_metered(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    return tonemap(position, textureLoad(exposure_tex, vec2<i32>(0), 0).r * EXPOSURE);
}

// With a host: the frame's exposure factor (FrameInputs::exposure) on top. A factor of 1
// multiplies exactly, so the image is the one fs_tonemap draws.
@fragment
fn fs_tonemap_frame(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    return tonemap(position, EXPOSURE * light_info.exposure);
}

@fragment
fn fs_tonemap_frame_metered(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let metered = textureLoad(exposure_tex, vec2<i32>(0), 0).r * EXPOSURE;
    return tonemap(position, metered * light_info.exposure);
}

// In compute (`stage: compute`): the same per pixel, stored sRGB-encoded by hand into an
// rgba8unorm storage texture (no sRGB format is a storage format), so the bytes are an
// sRGB target's. No ROPs: a full-screen fragment pass pays them for every pixel it
// writes (0.68 ms at 3840x2160 on the H200 since it overwrites its target rather than
// clearing it first, 1.27 before; this takes 0.08).
@group(1) @binding(2) var out_tex: texture_storage_2d<rgba8unorm, write>;

fn srgb_encode(c: vec3<f32>) -> vec3<f32> {
    return select(1.055 * pow(c, vec3<f32>(1.0 / 2.4)) - 0.055, 12.92 * c, c <= vec3<f32>(0.0031308));
}

fn store_tonemapped(pixel: vec2<u32>, exposure: f32) {
    if any(pixel >= textureDimensions(out_tex)) {
        return;
    }
    let mapped = tonemap(vec4<f32>(vec2<f32>(pixel) + 0.5, 0.0, 1.0), exposure);
    // Rounded here, to the nearest of the 256 levels, and stored a quarter level above
    // it: a device converting to unorm by truncation or by rounding keeps that level
    // (the H200's storage writes and its sRGB targets otherwise differed by a level on
    // many pixels).
    let level = floor(srgb_encode(mapped.rgb) * 255.0 + 0.5);
    textureStore(out_tex, pixel, vec4<f32>((level + 0.25) / 255.0, 1.0));
}

@compute @workgroup_size(8, 8)
fn cs_tonemap(@builtin(global_invocation_id) id: vec3<u32>) {
    store_tonemapped(id.xy, EXPOSURE);
}

@compute @workgroup_size(8, 8)
fn cs_tonemap_metered(@builtin(global_invocation_id) id: vec3<u32>) {
    store_tonemapped(id.xy, textureLoad(exposure_tex, vec2<i32>(0), 0).r * EXPOSURE);
}

@compute @workgroup_size(8, 8)
fn cs_tonemap_frame(@builtin(global_invocation_id) id: vec3<u32>) {
    store_tonemapped(id.xy, EXPOSURE * light_info.exposure);
}

@compute @workgroup_size(8, 8)
fn cs_tonemap_frame_metered(@builtin(global_invocation_id) id: vec3<u32>) {
    let metered = textureLoad(exposure_tex, vec2<i32>(0), 0).r * EXPOSURE;
    store_tonemapped(id.xy, metered * light_info.exposure);
}
