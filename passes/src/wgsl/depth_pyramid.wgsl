// The depth pyramid (passes/depth_pyramid.rs): each texel of each level the farthest
// depth (reversed-Z: the least) of every sample of every pixel it covers, which occlusion
// culling tests clusters against (cluster_occlusion.wgsl). Level 0 from a compute
// raster's keys: of a W x H output and a level of N x M texels, texel (i, j) covers the
// pixels from floor(i W / N) to ceil((i + 1) W / N) - 1 across, and likewise down, so
// every pixel lies in texel (floor(x N / W), floor(y M / H)) whatever the two sizes (texels
// on a border between pixels take both). Each further level from the one before, a texel
// per 2 x 2, the last texel of a row or column taking the rest (a third at an odd size):
// texel t of level 0 lies in texel min(t >> k, size - 1) of level k. Every sample is read,
// not sample 0 alone where a pixel shows one triangle: the samples' depths differ across
// a sloped triangle, and the test must hold for each. Composed after common.wgsl,
// scene.wgsl, key_layout.wgsl and visibility_samples.wgsl (the keys, group 1 binding 8).

@group(1) @binding(0) var level_out: texture_storage_2d<r32float, write>;
@group(1) @binding(1) var level_in: texture_storage_2d<r32float, read>;

// Above every depth (reversed-Z depths lie in [0, 1]): what min starts from.
const NEAREST: f32 = 2.0;

@compute @workgroup_size(8, 8)
fn cs_pyramid_keys(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(level_out);
    if any(id.xy >= size) {
        return;
    }
    let output = vec2<u32>(camera.viewport);
    let first = id.xy * output / size;
    let end = ((id.xy + 1u) * output + size - 1u) / size;
    var farthest = NEAREST;
    for (var y = first.y; y < end.y; y++) {
        for (var x = first.x; x < end.x; x++) {
            for (var s = 0u; s < SAMPLES; s++) {
                farthest = min(farthest, sample_depth(vec2<i32>(vec2<u32>(x, y)), s));
            }
        }
    }
    textureStore(level_out, id.xy, vec4<f32>(farthest, 0.0, 0.0, 0.0));
}

@compute @workgroup_size(8, 8)
fn cs_pyramid_level(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(level_out);
    if any(id.xy >= size) {
        return;
    }
    let below = textureDimensions(level_in);
    let first = 2u * id.xy;
    let last = select(first + 1u, below - 1u, id.xy == size - 1u);
    var farthest = NEAREST;
    for (var y = first.y; y <= last.y; y++) {
        for (var x = first.x; x <= last.x; x++) {
            farthest = min(farthest, textureLoad(level_in, vec2<u32>(x, y)).x);
        }
    }
    textureStore(level_out, id.xy, vec4<f32>(farthest, 0.0, 0.0, 0.0));
}
