// The transparent pass: alpha BLEND meshes drawn back to front into an accumulation
// target, shaded as forward.wgsl shades (its vertex stages, its `shade_surface`: the same
// material model and every light of lighting.wgsl), with the surface's base alpha for
// the pipeline's blending (common/gpu/scene_draw.rs). Composed after forward.wgsl.

@fragment
fn fs_blend_pixel(in: PixelVaryings, @builtin(front_facing) front: bool) -> @location(0) vec4<f32> {
    return shade_surface(pixel_attributes(in, front), front);
}

@fragment
fn fs_blend_sample(in: SampleVaryings, @builtin(front_facing) front: bool) -> @location(0) vec4<f32> {
    return shade_surface(sample_attributes(in, front), front);
}

// The accumulation's start where blended meshes may lie (passes/transparent.rs, `extent:
// blended`): nothing blended over black, transmittance 1. Drawn with common.wgsl's
// vs_fullscreen, scissored, before the meshes.
@fragment
fn fs_accumulation_start() -> @location(0) vec4<f32> {
    return vec4<f32>(0.0, 0.0, 0.0, 1.0);
}
