// The lean G-buffer's view depth: no channel of its own, but the depth buffer's sample
// (the reader's sample_depth) unprojected at the sample's position. 0 where nothing was drawn, as
// the stored channel has it: FAR_DEPTH is the depth convention's clear value (0 with
// reversed-Z, 1 without), which no drawn sample keeps.

// Each sample's own depth: the samples of one fragment differ along its slope.
const STORED_VIEW_DEPTH: bool = false;

fn load_view_depth(pixel: vec2<i32>, s: u32) -> f32 {
    let depth = sample_depth(pixel, s);
    if depth == FAR_DEPTH {
        return 0.0;
    }
    return dot(unproject(sample_position(pixel, s), depth), camera.forward);
}
