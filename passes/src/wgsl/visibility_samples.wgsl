// A visibility buffer in a compute rasteriser's buffer (passes/visibility_compute.rs,
// common/visibility_samples.rs) as its readers take it, group 1, binding 8, laid out as
// key_layout.wgsl says. Composed after common.wgsl, scene.wgsl and key_layout.wgsl.

@group(1) @binding(8) var<storage, read> sample_keys: array<vec2<u32>>;

fn key_at(pixel: vec2<i32>, s: u32) -> vec2<u32> {
    return sample_keys[key_index(vec2<u32>(pixel), s)];
}

fn sample_id(pixel: vec2<i32>, s: u32) -> u32 {
    return key_at(pixel, s).x;
}

fn sample_depth(pixel: vec2<i32>, s: u32) -> f32 {
    return bitcast<f32>(key_at(pixel, s).y & ~SEVERAL_SURFACES);
}

// Whether every sample of `pixel` shows sample 0's triangle, from sample 0's key alone.
fn one_surface(pixel: vec2<i32>) -> bool {
    return (key_at(pixel, 0u).y & SEVERAL_SURFACES) == 0u;
}
