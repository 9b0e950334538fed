// taa.wgsl's `hidden_share` from a history of the motion texture (group 1, binding 4: the
// previous frame's motion, each pixel's motion then in red and green and its view depth
// then in blue): the share of the history read at the reprojected point that shows a
// surface which hid the pixel's point in the previous frame (a moving object uncovering
// what is behind), so that taa takes at least that share of this frame. A texel of the
// point's bilinear footprint counts, by its bilinear weight, where it shows a surface
//
// - nearer than the point was (the pixel's motion's alpha), by more than DEPTH_TOLERANCE
//   of that depth plus `slope`: the texels lie up to a pixel from the point on either
//   axis, so on a surface seen at a slant they are nearer by up to its change of view
//   depth per pixel along x plus along y (taa.wgsl finds it in this frame's
//   neighbourhood);
// - and moving apart from it, by more than MOTION_APART pixels a frame: only a surface
//   that moved across the point can have uncovered it. A still camera's jitter shows a
//   thin surface in front in one frame and misses it in the next, on the same pixel:
//   its history is anti-aliasing, not a ghost.
//
// Weighed by share, a footprint straddling the hiding surface's old edge takes the frame
// in part, and one wholly on it takes the frame alone.

@group(1) @binding(4) var motion_history_tex: texture_2d<f32>;

// The share of the point's previous view depth by which the history's must be nearer
// beyond the slope's allowance: well above the half floats' rounding (1/2048), and what
// a curved surface leaves off its slope over a pixel.
const DEPTH_TOLERANCE: f32 = 0.02;
// Pixels a frame. Measured on lavapipe (`rgraph bench --motion orbit:20`, 320x180):
// 0.5, 1 and 2 lower builtin:spheres' sequence FLIP and instability alike, and below 2
// builtin:dense's thin geometry, its parallax uncovering it now and then by a sample,
// flickers more than with no rejection at all.
const MOTION_APART: f32 = 2.0;

fn hidden_share(previous: vec2<f32>, depth_before: f32, slope: f32, motion: vec2<f32>) -> f32 {
    let last = vec2<i32>(textureDimensions(motion_history_tex)) - 1;
    let corner = floor(previous - 0.5);
    let f = previous - 0.5 - corner;
    let nearer = depth_before * (1.0 - DEPTH_TOLERANCE) - slope;
    var share = 0.0;
    for (var y = 0; y < 2; y++) {
        for (var x = 0; x < 2; x++) {
            let w = select(1.0 - f, f, vec2<bool>(x == 1, y == 1));
            let at = clamp(vec2<i32>(corner) + vec2<i32>(x, y), vec2<i32>(0), last);
            let m = textureLoad(motion_history_tex, at, 0);
            let apart = distance(m.xy, motion) > MOTION_APART;
            share += select(0.0, w.x * w.y, m.z < nearer && apart);
        }
    }
    return share;
}
