// What a sample emits where the scene has no emission and the G-buffer no channel for it:
// an unlit surface's color (albedo), else BACKGROUND (generated) where nothing was drawn.

fn emitted(pixel: vec2<i32>, s: u32, g: GSample) -> vec3<f32> {
    if (g.flags & FLAG_UNLIT) != 0u {
        return g.albedo;
    }
    return select(vec3<f32>(0.0), BACKGROUND, g.view_depth <= 0.0);
}
