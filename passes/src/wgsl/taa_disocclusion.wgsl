// taa.wgsl's `disoccluded` from a history of the motion texture (group 1, binding 4:
// the previous frame's motion, whose blue is each pixel's view depth then): where the
// history is read, the previous frame showed a surface nearer than where the pixel's
// motion says its point was (the motion's alpha), so that surface hid the point, and
// the history shows it, not this pixel's surface (a moving object uncovering what is
// behind). Every texel the bilinear footprint of the reprojected point weighs is
// compared: where one shows the nearer surface the history read there mixes it in (the
// pixels along where the hiding surface's edge was). The texels lie up to a pixel from
// the point on either axis, so on a surface seen at a slant they may be nearer by up to
// `slope`, the surface's change of view depth per pixel along x plus along y (taa.wgsl
// finds it in this frame's neighbourhood).

@group(1) @binding(4) var motion_history_tex: texture_2d<f32>;

// The share of the point's previous view depth by which the history's must be nearer
// beyond the slope's allowance: well above the half floats' rounding (1/2048), and what
// a curved surface leaves off its slope over a pixel.
const DEPTH_TOLERANCE: f32 = 0.02;
// The least bilinear weight of a texel compared: one the read does not weigh (the point
// on a texel's centre) shows nothing of the history there.
const LEAST_WEIGHT: f32 = 1.0 / 64.0;

fn disoccluded(previous: vec2<f32>, depth_before: f32, slope: f32) -> bool {
    let last = vec2<i32>(textureDimensions(motion_history_tex)) - 1;
    let corner = floor(previous - 0.5);
    let f = previous - 0.5 - corner;
    let nearer = depth_before * (1.0 - DEPTH_TOLERANCE) - slope;
    var hidden = false;
    for (var y = 0; y < 2; y++) {
        for (var x = 0; x < 2; x++) {
            let w = select(1.0 - f, f, vec2<bool>(x == 1, y == 1));
            let at = clamp(vec2<i32>(corner) + vec2<i32>(x, y), vec2<i32>(0), last);
            let z = textureLoad(motion_history_tex, at, 0).z;
            hidden = hidden || (w.x * w.y >= LEAST_WEIGHT && z < nearer);
        }
    }
    return hidden;
}
