// The shadow maps' views (gpu_scene/shadows.rs writes them each frame), group 0 of the
// passes that draw or read the shadow atlas. Composed after scene.wgsl.

struct ShadowView {
    // Camera-relative world to the map's clip space: x and y in [-1, 1], depth in [0, 1]
    // (standard Z: 1 is the far plane, where the atlas is cleared).
    clip_from_world: mat4x4<f32>,
    // Where the map lies in the atlas: the offset (xy) and size (zw) of its tile, in UV.
    rect: vec4<f32>,
    // x: the world size of a texel (orthographic), or of a texel at distance 1 from the
    // light (perspective); y: a cascade's farthest view depth; z: 1 for a perspective
    // map; w: on a light's first view, the views it has.
    params: vec4<f32>,
}

struct ShadowViews {
    views: array<ShadowView, 512>,
}

@group(0) @binding(8) var<uniform> shadow_views: ShadowViews;
