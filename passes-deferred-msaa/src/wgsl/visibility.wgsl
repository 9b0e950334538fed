// The visibility-buffer raster pass: each opaque mesh drawn without index or vertex
// buffers (gpu_scene's pull_meshes), its vertices pulled from storage (geometry.wgsl), so
// the vertex index is the position in the scene's index buffer and index / 3 the
// triangle. Each sample keeps the nearest triangle's ID + 1 (0: nothing drawn), as
// geometry.wgsl's id_texel stores it. IDs are exact for every triangle an index buffer of
// u32 positions can hold.
// Composed after common.wgsl, scene.wgsl and geometry.wgsl.

struct Varyings {
    @builtin(position) clip: vec4<f32>,
    @location(0) @interpolate(flat) id: u32,
    // Base color alpha (factor times vertex color: masked materials without textures;
    // textured scenes take the G-buffer path), for alpha MASK.
    @location(1) alpha: f32,
    @location(2) @interpolate(flat) material: u32,
}

@vertex
fn vs_visibility(@builtin(vertex_index) index: u32, @builtin(instance_index) mesh_index: u32) -> Varyings {
    let mesh = meshes[mesh_index];
    let v = pull_vertex(index, mesh);
    var out: Varyings;
    out.clip = camera.view_proj * (mesh.model * vec4<f32>(v.position, 1.0));
    out.id = index / 3u + 1u;
    out.material = mesh.material;
    out.alpha = materials[mesh.material].base_color.a * v.color.a;
    return out;
}

@fragment
fn fs_visibility(in: Varyings) -> @location(0) vec2<u32> {
    return id_texel(in.id);
}

@fragment
fn fs_visibility_masked(in: Varyings) -> @location(0) vec2<u32> {
    if in.alpha < materials[in.material].alpha_cutoff {
        discard;
    }
    return id_texel(in.id);
}

// Without IDs (a depth pre-pass): depth only.
@fragment
fn fs_depth() {}

@fragment
fn fs_depth_masked(in: Varyings) {
    if in.alpha < materials[in.material].alpha_cutoff {
        discard;
    }
}
