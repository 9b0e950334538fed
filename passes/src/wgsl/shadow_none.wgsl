// No shadow maps: every light reaches every surface it faces (the passes without a
// shadow atlas, and the light passes where the scene has no shadowed light).
fn light_visibility(s: Surface, light: LightData) -> f32 {
    return 1.0;
}
