// What a sample emits where no G-buffer channel holds it: the emission its surface carries
// (a visibility buffer rebuilds it; a G-buffer without an emission channel is of a scene
// that emits nothing), an unlit surface's color (albedo), and BACKGROUND (generated) where
// nothing was drawn.

fn emitted(pixel: vec2<i32>, s: u32, g: GSample) -> vec3<f32> {
    if (g.flags & FLAG_UNLIT) != 0u {
        return g.albedo + g.emission;
    }
    return select(g.emission, BACKGROUND, g.view_depth <= 0.0);
}
