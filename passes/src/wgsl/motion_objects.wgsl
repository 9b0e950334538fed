// motion.wgsl's `pixel_motion` from a visibility buffer: the triangle sample 0 of the
// pixel shows (`sample_id`, from visibility_textures.wgsl or visibility_samples.wgsl),
// met by the ray through the pixel's centre (plane_hit.wgsl) at an object-space point
// that its mesh's previous transform takes to where it was (from where the triangle's
// vertices were, where a deformation moved them). Where nothing was drawn, the
// direction of the ray, which only the camera's turn moves. The motion in x and y, the
// view depth of the hit in z, and in w the point's view depth in the previous frame.
// Composed after motion.wgsl, geometry.wgsl, plane_hit.wgsl and the visibility buffer's
// reader.

// The previous positions (3 f32 each) of the scene's vertices Motion.deformed.x.., which
// the deformation replaced this frame (gpu_scene/deform.rs); read only.
@group(1) @binding(10) var<storage, read_write> replaced: array<f32>;

// Where the vertex at position `index` of the index buffer, in `mesh`, at `now` this
// frame, was in the previous frame's object space.
fn previous_position(index: u32, mesh: MeshData, now: vec3<f32>) -> vec3<f32> {
    let vertex = u32(i32(index_words[index]) + mesh.base_vertex);
    let d = motion.deformed;
    if d.z == 0u || vertex < d.x || vertex >= d.y {
        return now;
    }
    let at = (vertex - d.x) * 3u;
    return vec3<f32>(replaced[at], replaced[at + 1u], replaced[at + 2u]);
}

fn pixel_motion(pixel: vec2<i32>) -> vec4<f32> {
    let at = vec2<f32>(pixel) + 0.5;
    let id = sample_id(pixel, 0u);
    if id == 0u {
        return sky_motion(at);
    }
    let triangle = id - 1u;
    let m = mesh_of_triangle(triangle);
    let mesh = meshes[m];
    let o0 = pull_position(3u * triangle, mesh);
    let o1 = pull_position(3u * triangle + 1u, mesh);
    let o2 = pull_position(3u * triangle + 2u, mesh);
    let p0 = (mesh.model * vec4<f32>(o0, 1.0)).xyz;
    let e1 = (mesh.model * vec4<f32>(o1, 1.0)).xyz - p0;
    let e2 = (mesh.model * vec4<f32>(o2, 1.0)).xyz - p0;
    let hit = hit_plane(at, p0, e1, e2);
    let b = hit.b;
    let object = vec4<f32>(b.x * o0 + b.y * o1 + b.z * o2, 1.0);
    let q0 = previous_position(3u * triangle, mesh, o0);
    let q1 = previous_position(3u * triangle + 1u, mesh, o1);
    let q2 = previous_position(3u * triangle + 2u, mesh, o2);
    let before = vec4<f32>(b.x * q0 + b.y * q1 + b.z * q2, 1.0);
    let went = moved(motion.objects[2u * m] * object, motion.objects[2u * m + 1u] * before);
    return vec4<f32>(went.xy, view_depth(hit.origin + hit.ray * hit.along), went.z);
}
