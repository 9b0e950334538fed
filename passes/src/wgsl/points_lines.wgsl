// Points and lines (passes/points_lines.rs), after common.wgsl and scene.wgsl (the
// camera). Unlit, as the glTF sample viewer draws them: each vertex carries its final
// colour (base colour factor times COLOR_0, plus emission), computed on the CPU, its
// object-space position and its primitive, whose matrix places it. The
// accumulation target begins as (0, 0, 0, 1); a covered sample becomes (colour, 0), so
// composite.wgsl's `resolved * mean(T) + mean(C)` mixes the colour in by coverage.

struct Placement {
    // Where the matrices' world origin is, camera-relative: `models` take the vertices to
    // world positions minus an anchor near them (f32 keeps its precision there), and
    // this is the anchor minus the camera position (computed in f64 on the CPU).
    anchor: vec3<f32>,
    // A point's side in pixels of the target.
    point_size: f32,
    // The target's size in pixels.
    target_size: vec2<f32>,
    _pad: vec2<f32>,
}

@group(1) @binding(0) var<uniform> placement: Placement;
// Per primitive, from object space to world space minus the anchor: the frame's
// transforms, composed with the anchor in f64 on the CPU.
@group(1) @binding(1) var<storage, read> models: array<mat4x4<f32>>;

struct Stroke {
    @builtin(position) clip: vec4<f32>,
    @location(0) color: vec3<f32>,
}

fn stroke_clip(position: vec3<f32>, primitive: u32) -> vec4<f32> {
    let near_anchor = (models[primitive] * vec4<f32>(position, 1.0)).xyz;
    return camera.view_proj * vec4<f32>(near_anchor + placement.anchor, 1.0);
}

// A line's vertex: the rasteriser draws the segment one pixel wide.
@vertex
fn vs_line(
    @location(0) position: vec3<f32>,
    @location(1) color: vec3<f32>,
    @location(2) primitive: u32,
) -> Stroke {
    return Stroke(stroke_clip(position, primitive), color);
}

// A point's corner: two triangles (six vertices) per instance, a square of
// `point_size` pixels centred on the projected point, at its depth (wgpu has no point
// size, and its point list draws one pixel).
@vertex
fn vs_point(
    @builtin(vertex_index) corner: u32,
    @location(0) position: vec3<f32>,
    @location(1) color: vec3<f32>,
    @location(2) primitive: u32,
) -> Stroke {
    // Corners (-1, -1), (1, -1), (-1, 1), (-1, 1), (1, -1), (1, 1).
    let quad = array<vec2<f32>, 6>(
        vec2<f32>(-1.0, -1.0), vec2<f32>(1.0, -1.0), vec2<f32>(-1.0, 1.0),
        vec2<f32>(-1.0, 1.0), vec2<f32>(1.0, -1.0), vec2<f32>(1.0, 1.0),
    );
    var clip = stroke_clip(position, primitive);
    // Half the side in normalised device units is point_size / target_size, times w
    // before the divide.
    clip = vec4<f32>(clip.xy + quad[corner] * placement.point_size / placement.target_size * clip.w, clip.zw);
    return Stroke(clip, color);
}

@fragment
fn fs_stroke(in: Stroke) -> @location(0) vec4<f32> {
    return vec4<f32>(min(in.color, vec3<f32>(HALF_MAX)), 0.0);
}
