// Screen-space ambient occlusion: ground-truth-based AO (GTAO: Jimenez, Wu, Pesce and
// Jarabo, "Practical Realtime Strategies for Accurate Indirect Occlusion", 2016) on the
// G-buffer's view depth and normals, then a depth-aware (bilateral) blur. Composed after
// common.wgsl and scene.wgsl (the camera, group 0); inputs are group 1, like every
// deferred pass's. passes/ssao.rs documents the parameters.
//
// Multisampled G-buffers are read at sample 0, the sample light_nonedge shades a pixel
// from, so the occlusion and the surface it darkens agree on every pixel that is not an
// edge (passes/ssao.rs says why not the nearest or farthest sample).

@group(1) @binding(0) var normal_tex: GTexF;
@group(1) @binding(1) var view_depth_tex: GTexF;
// fs_blur's input: fs_gtao's output.
@group(1) @binding(2) var raw_ao_tex: texture_2d<f32>;

// World-space radius: occluders farther from the shaded point are ignored.
override RADIUS: f32 = 0.5;
// Slices (directions in the screen) per pixel, each searched both ways.
override DIRECTIONS: u32 = 4u;
// Depth samples per slice side.
override STEPS: u32 = 4u;
// An occluder counts only above the tangent plane by this much (the sine of its
// elevation): on a plane, rounding must not make the surface occlude itself.
override BIAS: f32 = 0.05;
// fs_blur: a neighbour's weight falls from 1 to 0 as its view depth departs from the
// pixel's by this fraction of it.
override BLUR_DEPTH: f32 = 0.05;
// G-buffer pixels per AO texel side: 1 at full resolution, 2 at half (passes/ssao.rs).
// At half resolution a texel's occlusion is its 2 x 2 block's top-left pixel's.
override SCALE: i32 = 1;

const HALF_PI: f32 = 1.5707963267949;

fn g_depth(pixel: vec2<i32>) -> f32 {
    return textureLoad(view_depth_tex, pixel, 0).r;
}

fn in_image(pixel: vec2<i32>) -> bool {
    let size = vec2<i32>(textureDimensions(view_depth_tex));
    return all(pixel >= vec2<i32>(0)) && all(pixel < size);
}

// The cosine-weighted visible arc of one slice side, from the view vector to horizon
// angle `h`, for the normal at angle `n` in the slice (GTAO's equation 10, half of it).
fn arc(h: f32, n: f32) -> f32 {
    return 0.25 * (-cos(2.0 * h - n) + cos(n) + 2.0 * h * sin(n));
}

// 4 x 4 ordered (Bayer) offsets in [0, 16): neighbouring pixels rotate their slices by
// different sixteenths, and fs_blur's 4 x 4 window averages all sixteen.
const BAYER = array<u32, 16>(0u, 8u, 2u, 10u, 12u, 4u, 14u, 6u, 3u, 11u, 1u, 9u, 15u, 7u, 13u, 5u);

@fragment
fn fs_gtao(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let texel = pixel_of(position);
    let pixel = texel * SCALE;
    let z = g_depth(pixel);
    // No geometry: nothing to occlude.
    if z <= 0.0 {
        return vec4<f32>(1.0);
    }
    let center = vec2<f32>(pixel) + 0.5;
    let p = surface_position(center, z);
    let n = oct_decode(textureLoad(normal_tex, pixel, 0).xy);
    // Toward the camera along the pixel's ray (for orthographic cameras too).
    let v = safe_normalize(p - surface_position(center, z + 1.0));
    // One pixel to the right at this depth, in world units: the radius in pixels.
    let pixel_size = length(surface_position(center + vec2<f32>(1.0, 0.0), z) - p);
    let radius_px = RADIUS / max(pixel_size, 1e-20);
    // Less than a pixel: no other pixel's depth lies within the radius.
    if radius_px < 1.0 {
        return vec4<f32>(1.0);
    }
    // By AO texel, so that fs_blur's window of 4 x 4 texels holds all sixteen rotations.
    let tile = (u32(texel.x) & 3u) + 4u * (u32(texel.y) & 3u);
    let rotation = (f32(BAYER[tile]) + 0.5) / 16.0;
    let stride = (f32(tile) + 0.5) / 16.0;

    var visible = 0.0;
    var unoccluded = 0.0;
    for (var i = 0u; i < DIRECTIONS; i++) {
        let phi = (f32(i) + rotation) * PI / f32(DIRECTIONS);
        let d = vec2<f32>(cos(phi), sin(phi));
        // The slice: the plane through the view ray and the screen direction d.
        let along = surface_position(center + d, z) - p;
        let ortho = safe_normalize(along - v * dot(along, v));
        let axis = cross(ortho, v);
        let projected = n - axis * dot(n, axis);
        let length_n = length(projected);
        let cos_n = clamp(dot(projected, v) / max(length_n, 1e-20), -1.0, 1.0);
        let angle_n = select(-1.0, 1.0, dot(projected, ortho) >= 0.0) * acos(cos_n);
        // Horizons start at the tangent plane: only occluders raise them.
        var h = vec2<f32>(angle_n - HALF_PI, angle_n + HALF_PI);
        for (var side = 0; side < 2; side++) {
            let sign = f32(side * 2 - 1);
            for (var j = 0u; j < STEPS; j++) {
                let t = 1.0 + (f32(j) + stride) / f32(STEPS) * (radius_px - 1.0);
                let q = vec2<i32>(floor(center + sign * d * t));
                if !in_image(q) {
                    break;
                }
                let zq = g_depth(q);
                if zq <= 0.0 {
                    continue;
                }
                let delta = surface_position(vec2<f32>(q) + 0.5, zq) - p;
                let distance = length(delta);
                if distance > RADIUS || distance <= 0.0 || dot(delta, n) <= BIAS * distance {
                    continue;
                }
                let angle = atan2(dot(delta, ortho), dot(delta, v));
                if side == 0 {
                    h.x = max(h.x, angle);
                } else {
                    h.y = min(h.y, angle);
                }
            }
        }
        visible += length_n * (arc(h.x, angle_n) + arc(h.y, angle_n));
        unoccluded += length_n * (arc(angle_n - HALF_PI, angle_n) + arc(angle_n + HALF_PI, angle_n));
    }
    // Normalised by the same slices without occluders, so a surface with nothing above it
    // is exactly 1 whatever its tilt and the slice count; occluders only narrow the arcs,
    // and the clamp keeps rounding from brightening. A surface seen exactly edge-on by
    // its only slice has no arc to measure: unoccluded.
    let ao = select(1.0, clamp(visible / unoccluded, 0.0, 1.0), unoccluded > 1e-6);
    return vec4<f32>(ao, ao, ao, 1.0);
}

// The bilateral blur: the 4 x 4 window of AO texels fs_gtao's rotations repeat over,
// each weighted by how close the view depth it was computed at is to the pixel's, so
// occlusion does not bleed across silhouettes; at half resolution the same weights
// upsample it. Writes the AO to r8unorm, or as grey to a display target (the debug
// view).
@fragment
fn fs_blur(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let pixel = pixel_of(position);
    let z = g_depth(pixel);
    if z <= 0.0 {
        return vec4<f32>(1.0);
    }
    let texels = vec2<i32>(textureDimensions(raw_ao_tex));
    let base = min(pixel / SCALE, texels - 1);
    var sum = 0.0;
    var weights = 0.0;
    for (var y = -2; y < 2; y++) {
        for (var x = -2; x < 2; x++) {
            let q = base + vec2<i32>(x, y);
            if any(q < vec2<i32>(0)) || any(q >= texels) {
                continue;
            }
            let w = max(0.0, 1.0 - abs(g_depth(q * SCALE) - z) / (BLUR_DEPTH * z));
            sum += w * textureLoad(raw_ao_tex, q, 0).r;
            weights += w;
        }
    }
    // At full resolution the pixel itself weighs 1; at half, a pixel unlike every texel
    // around it (a thin sliver) takes its own block's.
    var ao = textureLoad(raw_ao_tex, base, 0).r;
    if weights > 0.0 {
        ao = sum / weights;
    }
    return vec4<f32>(ao, ao, ao, 1.0);
}
