// Scene depth for the particle passes (seed 001): a depth buffer's value as view depth,
// the distance along the view direction that particles.wgsl compares its billboards
// with and depth_downsample.wgsl takes the maximum of. Composed after scene.wgsl; the
// pass binds group 0 with the camera of its depth buffer's convention and gives
// FAR_DEPTH, the value the buffer is cleared to.

// Where nothing was drawn: farther than any particle (a finite f32, so differences stay
// finite).
const FAR_VIEW_DEPTH: f32 = 1.0e30;

// A perspective or orthographic projection maps view depth to clip depth alone, so any
// pixel's ray gives it: the centre's.
fn view_depth_of(depth: f32) -> f32 {
    if depth == FAR_DEPTH {
        return FAR_VIEW_DEPTH;
    }
    return min(dot(unproject(camera.viewport * 0.5, depth), camera.forward), FAR_VIEW_DEPTH);
}
