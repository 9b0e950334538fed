// motion_meshes.wgsl's `last_pose_offset` from a G-buffer's pose offset (group 1, binding
// 2; common/pose_offset.rs): where sample 0's point was in the last pose, from where it
// is, in world space, so that the point's mesh's matrices take it back with the point
// (a skinned arm's pixel moves with its vertices). Only in a frame whose pose changed
// (`motion.deformed.z`, which motion_vectors.rs sets once per change of frame inputs):
// in the others the target holds an older pose's offsets, and no vertex moved.

@group(1) @binding(2) var pose_tex: GTexF;

fn last_pose_offset(pixel: vec2<i32>) -> vec3<f32> {
    if motion.deformed.z == 0u {
        return vec3<f32>(0.0);
    }
    return textureLoad(pose_tex, pixel, 0).xyz;
}
