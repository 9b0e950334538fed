// A visibility buffer in a compute rasteriser's buffer (passes/visibility_compute.rs,
// common/visibility_samples.rs), group 1, binding 8: per pixel, row by row, each sample's 64-bit key
// read as two words, the triangle's ID + 1 low and the reversed-Z depth's bits high (0 0:
// nothing drawn, at the far depth 0).

@group(1) @binding(8) var<storage, read> sample_keys: array<vec2<u32>>;

fn key_at(pixel: vec2<i32>, s: u32) -> vec2<u32> {
    let row = u32(camera.viewport.x);
    return sample_keys[(u32(pixel.y) * row + u32(pixel.x)) * SAMPLES + s];
}

fn sample_id(pixel: vec2<i32>, s: u32) -> u32 {
    return key_at(pixel, s).x;
}

fn sample_depth(pixel: vec2<i32>, s: u32) -> f32 {
    return bitcast<f32>(key_at(pixel, s).y);
}
