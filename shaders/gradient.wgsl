// A vertical gradient between two linear HDR colors, for the `fullscreen` plugin (which
// provides `uv`, (0, 0) at the top left).

struct Gradient {
    top: vec4<f32>,
    bottom: vec4<f32>,
}

@group(0) @binding(0) var<uniform> gradient: Gradient;

@fragment
fn fs_main(@location(0) uv: vec2<f32>) -> @location(0) vec4<f32> {
    return mix(gradient.top, gradient.bottom, uv.y);
}
