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

// What shows where nothing is drawn (passes/background.rs): 0 what the image holds (black,
// or the environment a background pass added to it); 1 BACKGROUND_COLOR (linear), under
// the image by the background's transmittance, which a background pass left in the HDR
// image's alpha; 2 nothing: the output's alpha is the image's coverage (1 minus that
// transmittance) and its colour is unpremultiplied, an RGBA image for compositing.
override BACKGROUND: u32 = 0u;
override BACKGROUND_R: f32 = 0.0;
override BACKGROUND_G: f32 = 0.0;
override BACKGROUND_B: f32 = 0.0;

fn tonemap(position: vec4<f32>, exposure: f32) -> vec4<f32> {
    // An additive blend past the half-float range may store infinity (devices differ:
    // lavapipe saturates); clamped first, it maps to white instead of inf / inf = NaN.
    let texel = textureLoad(hdr_tex, pixel_of(position), 0);
    let stored = clamp(texel.rgb, vec3<f32>(0.0), vec3<f32>(HALF_MAX));
    var c = stored * exposure;
    // The surfaces' share of the pixel: their colour over it is what is tone mapped (a
    // pixel of nothing has none: black).
    var coverage = 1.0;
    if BACKGROUND != 0u {
        coverage = 1.0 - clamp(texel.a, 0.0, 1.0);
        c = select(vec3<f32>(0.0), c / coverage, coverage > 0.0);
    }
    var mapped = c;
    if OPERATOR == 1u {
        mapped = c / (1.0 + c);
    } else if OPERATOR == 2u {
        mapped = aces(c);
    }
    mapped = clamp(mapped, vec3<f32>(0.0), vec3<f32>(1.0));
    if BACKGROUND == 1u {
        let color = vec3<f32>(BACKGROUND_R, BACKGROUND_G, BACKGROUND_B);
        return vec4<f32>(mix(color, mapped, coverage), 1.0);
    }
    return vec4<f32>(mapped, coverage);
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
    textureStore(out_tex, pixel, vec4<f32>((level + 0.25) / 255.0, mapped.a));
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
