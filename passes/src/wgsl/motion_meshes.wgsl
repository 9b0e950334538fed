// motion_depth.wgsl's `point_motion` from a G-buffer's mesh channel (group 1, binding 1:
// the mesh index + 1 of each sample, low half in red, 0 where no mesh drew): the point
// moves with its mesh. Per mesh, `motion.objects[2m]` and `[2m + 1]` take a point relative
// to this frame's camera to this frame's clip space and to where the mesh's previous
// transform and the previous camera had it (motion_vectors.rs composes them). Where a
// skin or morph targets moved the mesh's vertices, the point is first moved to where they
// had it, `last_pose_offset` (motion_pose.wgsl, or none), which the block after this one
// defines: the previous transform then takes it from there.

@group(1) @binding(1) var mesh_tex: GTexU;

fn point_motion(pixel: vec2<i32>, p: vec4<f32>) -> vec3<f32> {
    let texel = textureLoad(mesh_tex, pixel, 0);
    let mesh = texel.r | (texel.g << 16u);
    if mesh == 0u {
        return static_motion(p);
    }
    let m = mesh - 1u;
    let before = p + vec4<f32>(last_pose_offset(pixel), 0.0);
    return moved(motion.objects[2u * m] * p, motion.objects[2u * m + 1u] * before);
}
