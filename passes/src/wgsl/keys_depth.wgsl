// A compute rasteriser's visibility buffer as a depth buffer (passes/keys_depth.rs):
// shaded once per sample (it reads sample_index), each invocation writes its sample's
// depth, the key's reversed-Z clip depth. Composed after common.wgsl, scene.wgsl and
// visibility_samples.wgsl (the keys, group 1).

@fragment
fn fs_keys_depth(
    @builtin(position) position: vec4<f32>,
    @builtin(sample_index) s: u32,
) -> @builtin(frag_depth) f32 {
    return sample_depth(pixel_of(position), s);
}
