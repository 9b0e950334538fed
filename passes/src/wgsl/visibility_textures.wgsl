// A visibility buffer in a raster pass's targets (passes/visibility.rs): the IDs (group 1,
// binding 0, geometry.wgsl's texel_id) and the depth buffer (binding 5).

@group(1) @binding(0) var ids_tex: GTexU;
@group(1) @binding(5) var depth_tex: GTexD;

fn sample_id(pixel: vec2<i32>, s: u32) -> u32 {
    return texel_id(textureLoad(ids_tex, pixel, s));
}

fn sample_depth(pixel: vec2<i32>, s: u32) -> f32 {
    return textureLoad(depth_tex, pixel, s);
}

// Whether every sample of `pixel` shows sample 0's triangle: the raster pass records
// nothing more than the samples, so all of them are compared.
fn one_surface(pixel: vec2<i32>) -> bool {
    let id = sample_id(pixel, 0u);
    var one = true;
    for (var s = 1u; s < SAMPLES; s++) {
        one = one && sample_id(pixel, s) == id;
    }
    return one;
}
