// The shadow maps' raster (passes/shadow_maps.rs): each opaque mesh drawn depth only
// into one view's tile of the atlas (the viewport), by indexed draws (the vertex index is
// a vertex of the scene's buffer, which the hardware's vertex reuse shades once for the
// triangles around it), its vertices read from storage (geometry.wgsl) and projected by
// that view (shadow.wgsl's shadow_views). The view is
// a dynamic offset into group 1. Composed after common.wgsl, scene.wgsl, geometry.wgsl,
// material.wgsl, material_table.wgsl, plane_hit.wgsl, mask_texture.wgsl (the texture
// table in group 3, for alpha MASK) and shadow_views.wgsl.

// x: the view this draw renders.
@group(1) @binding(0) var<uniform> shadow_view: vec4<u32>;

@vertex
fn vs_shadow(@builtin(vertex_index) vertex: u32, @builtin(instance_index) mesh_index: u32) -> @builtin(position) vec4<f32> {
    let mesh = meshes[mesh_index];
    let world = mesh.model * vec4<f32>(position_at(vertex), 1.0);
    return shadow_views.views[shadow_view.x].clip_from_world * world;
}

// Depth only: the atlas has no colour.
@fragment
fn fs_shadow() {}

// An alpha MASK caster: what its fragments need to test the cutoff.
struct MaskedVaryings {
    @builtin(position) clip: vec4<f32>,
    // Base color alpha: the factor times the vertex color's.
    @location(0) alpha: f32,
    @location(1) uv0: vec2<f32>,
    @location(2) uv1: vec2<f32>,
    @location(3) @interpolate(flat) material: u32,
}

@vertex
fn vs_shadow_masked(@builtin(vertex_index) vertex: u32, @builtin(instance_index) mesh_index: u32) -> MaskedVaryings {
    let mesh = meshes[mesh_index];
    let v = vertex_at(vertex);
    var out: MaskedVaryings;
    out.clip = shadow_views.views[shadow_view.x].clip_from_world * (mesh.model * vec4<f32>(v.position, 1.0));
    out.alpha = materials[mesh.material].base_color.a * v.color.a;
    out.uv0 = v.uv;
    out.uv1 = v.uv1;
    out.material = mesh.material;
    return out;
}

// Texels whose base colour alpha is below the material's cutoff cast no shadow, as they
// draw nothing in the visibility and G-buffer passes: the factor and vertex alpha times
// the base colour texture's, read from the texture table at the fragment's coordinates,
// filtered by their change across the shadow map's texels.
@fragment
fn fs_shadow_masked(in: MaskedVaryings) {
    // Derivatives first, in uniform control flow.
    let point = TexCoords(in.uv0, in.uv1);
    let right = TexCoords(in.uv0 + dpdx(in.uv0), in.uv1 + dpdx(in.uv1));
    let down = TexCoords(in.uv0 + dpdy(in.uv0), in.uv1 + dpdy(in.uv1));
    var texel = 1.0;
    if mask_textured(in.material) {
        let m = materials[in.material];
        texel = table_texel(material_slots[in.material][0], m, 0u, point, right, down).a;
    }
    if in.alpha * texel < materials[in.material].alpha_cutoff {
        discard;
    }
}
