// gbuffer.wgsl's `last_pose` where the pass writes a pose offset (common/pose_offset.rs):
// where the deformation had a vertex of the scene's vertex buffer in the last pose, from
// the positions its last dispatch replaced (gpu_scene/last_pose.rs, group 3: vertices
// range.x..range.y, 3 f32 each, in their mesh's object space). Every other vertex stood
// where it stands. Read in the vertex stage, as the vertex buffer is.

@group(3) @binding(0) var<storage, read> last_positions: array<f32>;
@group(3) @binding(1) var<uniform> last_range: vec4<u32>;

fn last_pose(index: u32, position: vec3<f32>) -> vec3<f32> {
    if index < last_range.x || index >= last_range.y {
        return position;
    }
    let at = (index - last_range.x) * 3u;
    return vec3<f32>(last_positions[at], last_positions[at + 1u], last_positions[at + 2u]);
}
