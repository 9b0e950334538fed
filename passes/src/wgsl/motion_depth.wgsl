// motion.wgsl's `pixel_motion` from a depth buffer (common/opaque_depth.rs's block,
// group 1): the point sample 0 of the pixel holds, moved by `point_motion`, which the
// block after this one defines: motion_still.wgsl (it stays put in the world, so only the
// camera moves it) or, where a G-buffer records each sample's mesh, motion_meshes.wgsl
// (it moves with its mesh). Where nothing was drawn, the direction of the ray. The motion
// in x and y, the point's view depth in z, its previous one in w.

// The point is unprojected where sample 0 lies, whose depth it is: at the pixel's
// centre, a slope's depth would put it off the surface.
fn pixel_motion(pixel: vec2<i32>) -> vec4<f32> {
    let at = vec2<f32>(pixel) + SAMPLE_POSITIONS[0];
    let depth = sample_depth_at(pixel, 0u);
    if depth == FAR_DEPTH {
        return sky_motion(at);
    }
    let p = unproject(at, depth);
    let m = point_motion(pixel, vec4<f32>(p, 1.0));
    return vec4<f32>(m.xy, view_depth(p), m.z);
}
