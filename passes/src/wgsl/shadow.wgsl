// Shadow maps: the fraction of a light that reaches a surface, read from the shadow atlas
// (the `shadow_maps` pass's depth32float, or shadow_resolve's r32float on a GPU). Composed
// after common.wgsl, scene.wgsl, brdf.wgsl and shadow_views.wgsl, with a generated block
// binding the atlas as `shadow_atlas: texture_2d<f32>` (either format binds so: texels
// loaded or gathered, never filtered), its nearest sampler `shadow_texels`, and the filter
// as SHADOW_FILTER (common/shadows.rs).

// LightData::shadow of a light without a shadow map.
const NO_SHADOW: u32 = 0xffffffffu;
// shadow_cascade's answer outside every cascade.
const NO_CASCADE: u32 = 0xffffffffu;

// The generated SHADOW_FILTER: 0, one comparison at the nearest texel (`--shadows
// hard`); 1, percentage-closer filtering, a 3 x 3 grid of bilinear comparison taps one
// texel apart (`pcf`).

// The normal offset (Holbert, GDC 2011), in texels: the surface point moves this far
// along its normal before it is looked up, more as the light grazes it, so that the
// filter's footprint (up to two texels from the centre) stays above the surface the map
// saw. The raster's slope-scaled depth bias (shadow_raster.wgsl) covers the rest.
const NORMAL_OFFSET_TEXELS: f32 = 1.5;
// A depth margin, in texels of world size, for what the offset leaves.
const DEPTH_BIAS_TEXELS: f32 = 0.5;

// The fraction of `light` reaching surface `s`: 1 without a shadow map or outside its
// views, less where the map holds something nearer the light.
fn light_visibility(s: Surface, light: LightData) -> f32 {
    if light.shadow == NO_SHADOW {
        return 1.0;
    }
    var view = light.shadow;
    if light.kind == LIGHT_DIRECTIONAL {
        let c = shadow_cascade(s, light);
        if c == NO_CASCADE {
            return 1.0;
        }
        view += c;
    }
    if light.kind == LIGHT_POINT {
        // The cube face the light sees the point through, by the direction's largest
        // axis, in gpu_scene/shadows.rs's order: +x, -x, +y, -y, +z, -z.
        let d = s.position - light.position;
        let a = abs(d);
        if a.x >= a.y && a.x >= a.z {
            view += select(1u, 0u, d.x > 0.0);
        } else if a.y >= a.z {
            view += select(3u, 2u, d.y > 0.0);
        } else {
            view += select(5u, 4u, d.z > 0.0);
        }
    }
    return view_visibility(shadow_views.views[view], s, light);
}

// A directional light's cascade holding `s`: the first reaching past the point's view
// depth, or NO_CASCADE past the last (lit) and for a light without maps.
fn shadow_cascade(s: Surface, light: LightData) -> u32 {
    if light.shadow == NO_SHADOW || light.kind != LIGHT_DIRECTIONAL {
        return NO_CASCADE;
    }
    let view = light.shadow;
    let depth = dot(s.position, camera.forward);
    let cascades = u32(shadow_views.views[view].params.w);
    var c = 0u;
    while c + 1u < cascades && depth > shadow_views.views[view + c].params.y {
        c++;
    }
    return select(c, NO_CASCADE, depth > shadow_views.views[view + c].params.y);
}

// The fraction of the light of `v` reaching `s`.
fn view_visibility(v: ShadowView, s: Surface, light: LightData) -> f32 {
    // A texel's world size where the point is: fixed for a cascade, growing with the
    // distance for a spot light's perspective.
    var texel = v.params.x;
    var l = -light.direction;
    if v.params.z > 0.5 {
        let to_light = light.position - s.position;
        texel *= length(to_light);
        l = safe_normalize(to_light);
    }
    let n_l = clamp(dot(s.normal, l), 0.0, 1.0);
    let offset = s.normal * (texel * NORMAL_OFFSET_TEXELS * (1.0 - n_l + 0.25));
    let p = s.position + offset + l * (texel * DEPTH_BIAS_TEXELS);
    let clip = v.clip_from_world * vec4<f32>(p, 1.0);
    if clip.w <= 0.0 {
        return 1.0;
    }
    let ndc = clip.xyz / clip.w;
    if any(abs(ndc.xy) > vec2<f32>(1.0)) || ndc.z < 0.0 || ndc.z > 1.0 {
        return 1.0;
    }
    let in_tile = vec2<f32>(0.5 * ndc.x + 0.5, 0.5 - 0.5 * ndc.y);
    let size = vec2<f32>(textureDimensions(shadow_atlas));
    let tile = v.rect.zw * size;
    // Taps stay two texels inside the tile: its neighbours are other views.
    let at = clamp(in_tile * tile, vec2<f32>(2.0), tile - 2.0) + v.rect.xy * size;
    if SHADOW_FILTER == 0u {
        return select(0.0, 1.0, ndc.z <= shadow_depth(vec2<i32>(floor(at))));
    }
    // Nine bilinear comparison taps one texel apart, as a comparison sampler would take
    // them, summed texel by texel: the 4 x 4 texels from one left of and above the
    // centre tap's, each weighed by how many taps cover it and how much (per axis
    // 1 - f, 1, 1, f for the centre tap's bilinear fraction f; 9 in all), read as four
    // gathers of 2 x 2 texels rather than sixteen loads.
    let corner = at - 0.5;
    let first = vec2<i32>(floor(corner)) - 1;
    let f = fract(corner);
    let wx = vec4<f32>(1.0 - f.x, 1.0, 1.0, f.x);
    let wy = vec4<f32>(1.0 - f.y, 1.0, 1.0, f.y);
    let z = vec4<f32>(ndc.z);
    var lit = 0.0;
    for (var qy = 0; qy < 2; qy++) {
        for (var qx = 0; qx < 2; qx++) {
            // The corner shared by the quad's four texels: its gather reads them, as
            // (left, bottom), (right, bottom), (right, top), (left, top), the top being
            // the lesser row.
            let quad = first + 2 * vec2<i32>(qx, qy);
            let stored = textureGather(0, shadow_atlas, shadow_texels, vec2<f32>(quad + 1) / size);
            let seen = select(vec4<f32>(0.0), vec4<f32>(1.0), z <= stored);
            let left = wx[2 * qx];
            let right = wx[2 * qx + 1];
            let top = wy[2 * qy] * (left * seen.w + right * seen.z);
            lit += top + wy[2 * qy + 1] * (left * seen.x + right * seen.y);
        }
    }
    return lit / 9.0;
}

// The depth stored at atlas texel `t`.
fn shadow_depth(t: vec2<i32>) -> f32 {
    return textureLoad(shadow_atlas, t, 0).x;
}
