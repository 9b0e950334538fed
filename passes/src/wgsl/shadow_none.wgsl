// No shadow maps: every light reaches every surface it faces (the passes without a
// shadow atlas, and the light passes where the scene has no shadowed light).
fn light_visibility(s: Surface, light: LightData) -> f32 {
    return 1.0;
}

// No cascades either (shadow.wgsl's NO_CASCADE).
const NO_CASCADE: u32 = 0xffffffffu;

fn shadow_cascade(s: Surface, light: LightData) -> u32 {
    return NO_CASCADE;
}
