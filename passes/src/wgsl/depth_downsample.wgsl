// Depth downsampling for off-screen particles (seed 001 §23.3): the multisampled depth
// as view depth at the off-screen size, an invocation per off-screen pixel. Composed
// after common.wgsl, scene.wgsl and particle_depth.wgsl, then common/opaque_depth.rs's
// block reading the opaque passes' depth or a compute rasteriser's keys (group 1):
// `sample_depth_at` (a sample's clip depth, FAR_DEPTH where nothing was drawn) and
// `one_surface` (sample 0 speaks for every sample of the pixel); the output is group 1
// binding 1.
//
// TAPS = 1 point-samples: sample 0 of the full-resolution pixel under the off-screen
// pixel's centre (at scale 1, exactly what the full-resolution particle pass reads).
// TAPS = n > 1 takes the maximum view depth (the farthest) over every sample of n x n
// pixels spread evenly over the off-screen pixel's block, the seed's "maximum of depth
// samples" (it took 4: n = 2): silhouettes shrink, so particles behind a foreground
// object reach up to its edge instead of leaving a halo.

@group(1) @binding(1) var out_tex: texture_storage_2d<r32float, write>;

override TAPS: u32 = 1u;

fn sample_view_depth(pixel: vec2<i32>, s: u32) -> f32 {
    return view_depth_of(sample_depth_at(pixel, s));
}

// The farthest view depth among `pixel`'s samples.
fn farthest_in(pixel: vec2<i32>) -> f32 {
    var farthest = sample_view_depth(pixel, 0u);
    if !one_surface(pixel) {
        for (var s = 1u; s < SAMPLES; s++) {
            farthest = max(farthest, sample_view_depth(pixel, s));
        }
    }
    return farthest;
}

@compute @workgroup_size(8, 8)
fn cs_downsample(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(out_tex);
    if any(id.xy >= size) {
        return;
    }
    let full = coverage_size();
    // One off-screen pixel's extent in full-resolution pixels.
    let block = full / vec2<f32>(size);
    let last = vec2<i32>(full) - 1;
    let centre = (vec2<f32>(id.xy) + 0.5) * block;
    var depth: f32;
    if TAPS == 1u {
        let pixel = clamp(vec2<i32>(floor(centre)), vec2<i32>(0), last);
        depth = sample_view_depth(pixel, 0u);
    } else {
        let origin = centre - 0.5 * block;
        depth = -FAR_VIEW_DEPTH;
        for (var j = 0u; j < TAPS; j++) {
            for (var i = 0u; i < TAPS; i++) {
                let at = origin + (vec2<f32>(f32(i), f32(j)) + 0.5) / f32(TAPS) * block;
                let pixel = clamp(vec2<i32>(floor(at)), vec2<i32>(0), last);
                depth = max(depth, farthest_in(pixel));
            }
        }
    }
    textureStore(out_tex, id.xy, vec4<f32>(depth, 0.0, 0.0, 0.0));
}
