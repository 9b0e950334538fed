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
