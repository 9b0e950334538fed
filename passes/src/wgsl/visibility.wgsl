// The visibility-buffer raster pass: each opaque mesh drawn without index or vertex
// buffers (gpu_scene's pull_meshes), its vertices pulled from storage (geometry.wgsl), so
// the vertex index is the position in the scene's index buffer and index / 3 the
// triangle. Each sample keeps the nearest triangle's ID + 1 (0: nothing drawn), as
// geometry.wgsl's id_texel stores it. IDs are exact for every triangle an index buffer of
// u32 positions can hold.
// Composed after common.wgsl, scene.wgsl, geometry.wgsl, material.wgsl,
// material_table.wgsl, plane_hit.wgsl and mask_texture.wgsl (the texture table in group 3).

struct Varyings {
    @builtin(position) clip: vec4<f32>,
    @location(0) @interpolate(flat) id: u32,
    // Base color alpha (factor times vertex color; a base colour texture's alpha is read
    // from the texture table, mask_texture.wgsl), for alpha MASK.
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

// Alpha MASK at the pixel centre, as the compute raster tests it (tile_raster.wgsl's
// mask_passes): the texel where the pixel's ray meets the triangle.
fn masked_out(in: Varyings) -> bool {
    return in.alpha * mask_texel_alpha(in.id, in.clip.xy) < materials[in.material].alpha_cutoff;
}

@fragment
fn fs_visibility_masked(in: Varyings) -> @location(0) vec2<u32> {
    if masked_out(in) {
        discard;
    }
    return id_texel(in.id);
}

// Without IDs (a depth pre-pass): depth only.
@fragment
fn fs_depth() {}

@fragment
fn fs_depth_masked(in: Varyings) {
    if masked_out(in) {
        discard;
    }
}
