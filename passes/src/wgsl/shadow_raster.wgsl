// The shadow maps' raster (passes/shadow_maps.rs): each opaque mesh drawn depth only
// into one view's tile of the atlas (the viewport), its vertices pulled from storage
// (geometry.wgsl) and projected by that view (shadow.wgsl's shadow_views). The view is
// a dynamic offset into group 1. Composed after common.wgsl, scene.wgsl, geometry.wgsl
// and shadow_views.wgsl.

// x: the view this draw renders.
@group(1) @binding(0) var<uniform> shadow_view: vec4<u32>;

@vertex
fn vs_shadow(@builtin(vertex_index) index: u32, @builtin(instance_index) mesh_index: u32) -> @builtin(position) vec4<f32> {
    let mesh = meshes[mesh_index];
    let world = mesh.model * vec4<f32>(pull_position(index, mesh), 1.0);
    return shadow_views.views[shadow_view.x].clip_from_world * world;
}

// Depth only: the atlas has no colour.
@fragment
fn fs_shadow() {}
