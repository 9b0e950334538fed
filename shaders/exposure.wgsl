// Exposure and a Reinhard tone curve, one texel per invocation, for the `compute` plugin.

@group(0) @binding(0) var src: texture_2d<f32>;
@group(0) @binding(1) var dst: texture_storage_2d<rgba16float, write>;
// x: exposure scale; y, z, w: padding.
@group(0) @binding(2) var<uniform> exposure: vec4<f32>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(dst);
    if id.x >= size.x || id.y >= size.y {
        return;
    }
    let color = textureLoad(src, id.xy, 0).rgb * exposure.x;
    textureStore(dst, id.xy, vec4<f32>(color / (1.0 + color), 1.0));
}
