// The shadow atlas as the light passes read it (passes/shadow_resolve.rs): each texel's
// depth from the compute raster's keys, or the nearer of it and the hardware's depth of
// the alpha MASK meshes; the far plane (1) where nothing was drawn. Or, while nothing it
// shows moved, the last frame's atlas as it was.

@group(0) @binding(0) var<storage, read> shadow_keys: array<u32>;
@group(0) @binding(1) var drawn: texture_2d<f32>;
@group(0) @binding(2) var atlas: texture_storage_2d<r32float, write>;
@group(0) @binding(3) var previous: texture_2d<f32>;

// The depth the compute raster kept at texel `t`: its key's bits inverted (0: nothing).
fn key_depth(t: vec2<u32>) -> f32 {
    let key = shadow_keys[t.y * textureDimensions(atlas).x + t.x];
    return select(1.0, bitcast<f32>(~key), key != 0u);
}

// The hardware's depth at texel `t` (cleared to 1).
fn drawn_depth(t: vec2<u32>) -> f32 {
    return textureLoad(drawn, t, 0).x;
}

// The keys alone.
@compute @workgroup_size(8, 8)
fn cs_resolve_keys(@builtin(global_invocation_id) id: vec3<u32>) {
    if all(id.xy < textureDimensions(atlas)) {
        textureStore(atlas, id.xy, vec4<f32>(key_depth(id.xy), 0.0, 0.0, 1.0));
    }
}

// The nearer of both.
@compute @workgroup_size(8, 8)
fn cs_resolve_both(@builtin(global_invocation_id) id: vec3<u32>) {
    if all(id.xy < textureDimensions(atlas)) {
        let depth = min(key_depth(id.xy), drawn_depth(id.xy));
        textureStore(atlas, id.xy, vec4<f32>(depth, 0.0, 0.0, 1.0));
    }
}

// The last frame's atlas, kept.
@compute @workgroup_size(8, 8)
fn cs_keep(@builtin(global_invocation_id) id: vec3<u32>) {
    if all(id.xy < textureDimensions(atlas)) {
        textureStore(atlas, id.xy, textureLoad(previous, id.xy, 0));
    }
}
