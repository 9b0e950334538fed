// motion_depth.wgsl's `point_motion` where nothing says which object a depth buffer's
// sample shows: the point stays put in the world, so only the camera moves it.

fn point_motion(pixel: vec2<i32>, p: vec4<f32>) -> vec3<f32> {
    return static_motion(p);
}
