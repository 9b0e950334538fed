// Depth downsampling for off-screen particles (seed 001 §23.3): the multisampled depth
// buffer as view depth at the off-screen size. Composed after common.wgsl, scene.wgsl
// and particle_depth.wgsl; the depth aspect in group 1.
//
// TAPS = 1 point-samples: sample 0 of the full-resolution pixel under the off-screen
// pixel's centre (at scale 1, exactly what the full-resolution particle pass reads).
// TAPS = n > 1 takes the maximum view depth (the farthest) over every sample of n x n
// pixels spread evenly over the off-screen pixel's block, the seed's "maximum of depth
// samples" (it took 4: n = 2): silhouettes shrink, so particles behind a foreground
// object reach up to its edge instead of leaving a halo.

@group(1) @binding(0) var scene_depth: GTexD;

override TAPS: u32 = 1u;

struct Block {
    @builtin(position) position: vec4<f32>,
    // 0..1 across the target, y down: times the full-resolution size, the position in
    // full-resolution pixels, whatever the off-screen size.
    @location(0) uv: vec2<f32>,
}

@vertex
fn vs_block(@builtin(vertex_index) index: u32) -> Block {
    let position = fullscreen_position(index, 0.0);
    return Block(position, vec2<f32>(0.5 + 0.5 * position.x, 0.5 - 0.5 * position.y));
}

@fragment
fn fs_downsample(in: Block) -> @location(0) vec4<f32> {
    let full = vec2<f32>(textureDimensions(scene_depth));
    // One off-screen pixel's extent in full-resolution pixels.
    let block = vec2<f32>(abs(dpdx(in.uv.x)), abs(dpdy(in.uv.y))) * full;
    let last = vec2<i32>(full) - 1;
    let centre = in.uv * full;
    if TAPS == 1u {
        let pixel = clamp(vec2<i32>(floor(centre)), vec2<i32>(0), last);
        return vec4<f32>(view_depth_of(textureLoad(scene_depth, pixel, 0)), 0.0, 0.0, 0.0);
    }
    let origin = centre - 0.5 * block;
    var farthest = -FAR_VIEW_DEPTH;
    for (var j = 0u; j < TAPS; j++) {
        for (var i = 0u; i < TAPS; i++) {
            let at = origin + (vec2<f32>(f32(i), f32(j)) + 0.5) / f32(TAPS) * block;
            let pixel = clamp(vec2<i32>(floor(at)), vec2<i32>(0), last);
            for (var s = 0u; s < SAMPLES; s++) {
                farthest = max(farthest, view_depth_of(textureLoad(scene_depth, pixel, s)));
            }
        }
    }
    return vec4<f32>(farthest, 0.0, 0.0, 0.0);
}
