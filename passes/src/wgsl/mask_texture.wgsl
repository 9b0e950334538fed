// The texel an alpha MASK tests beside its factor and vertex alpha: the base colour
// texture's alpha, read from the scene's texture table (material_table.wgsl, group 3) at
// the point of the triangle a pixel coordinate sees, filtered as shading filters it there
// (plane_hit.wgsl's ray differentials). Both visibility rasters take it, so a masked
// texture cuts the same pixels on a GPU (tile_raster.wgsl) and a CPU adapter
// (visibility.wgsl). Composed after geometry.wgsl, material.wgsl, material_table.wgsl
// and plane_hit.wgsl.

// Whether some alpha MASK material of the scene has a base colour texture (the scene's
// feature `mask_textures`; the default is the general shader): without one every masked
// texel is white and the code is compiled out.
override MASK_TEXTURES: bool = true;

// Whether material `index` is masked by a texture: its base colour slot has one.
fn mask_textured(index: u32) -> bool {
    return MASK_TEXTURES && (material_slots[index][0] & NO_LAYER) != NO_LAYER;
}

// The base colour texel's alpha of triangle `id` (+ 1) where the ray through pixel
// coordinate `at` meets its plane; 1 without a base colour texture.
fn mask_texel_alpha(id: u32, at: vec2<f32>) -> f32 {
    if !MASK_TEXTURES {
        return 1.0;
    }
    let triangle = id - 1u;
    let mesh = meshes[mesh_of_triangle(triangle)];
    if !mask_textured(mesh.material) {
        return 1.0;
    }
    let v0 = pull_vertex(3u * triangle, mesh);
    let v1 = pull_vertex(3u * triangle + 1u, mesh);
    let v2 = pull_vertex(3u * triangle + 2u, mesh);
    let p0 = (mesh.model * vec4<f32>(v0.position, 1.0)).xyz;
    let e1 = (mesh.model * vec4<f32>(v1.position, 1.0)).xyz - p0;
    let e2 = (mesh.model * vec4<f32>(v2.position, 1.0)).xyz - p0;
    let b = hit_plane(at, p0, e1, e2).b;
    let step = quad_steps(at, b, p0, e1, e2);
    let m = materials[mesh.material];
    let word = material_slots[mesh.material][0];
    return table_texel(word, m, 0u, tex_coords(b, v0, v1, v2), tex_coords(step.right, v0, v1, v2), tex_coords(step.down, v0, v1, v2)).a;
}
