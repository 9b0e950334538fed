// `load_layers` of a G-buffer that stores no material layers, or of a pass that reads its
// core channels only (the edge pass, the debug views, the G-buffer resolve): every
// sample's layers are the core model's. Passes that light a G-buffer storing layers get
// common/gbuffer_layers.rs's generated one instead.

fn load_layers(pixel: vec2<i32>, s: u32, normal: vec3<f32>) -> Layers {
    return plain_layers();
}
