// Temporal anti-aliasing (passes/taa.rs): this frame's image, drawn with a jittered
// camera, blended into the previous frame's result reprojected by the motion vectors.
// The history is read bilinearly where the pixel's surface was, clamped to the box this
// frame's 3 x 3 neighbourhood spans in YCoCg (Karis, "High quality temporal
// supersampling", 2014; Salvi's YCoCg box), so what the history shows of a surface no
// longer there (a ghost) cannot outlast one frame where its colour lies outside that
// box; then this frame weighs `current_weight` (the pass sets it each frame: 1 after a
// reset, 1 / n for the n-th frame since, down to 1 - the history weight). Where the
// previous position is off screen the frame is taken alone. Composed after common.wgsl.

@group(1) @binding(0) var current_tex: texture_2d<f32>;
@group(1) @binding(1) var motion_tex: texture_2d<f32>;
@group(1) @binding(2) var history_tex: texture_2d<f32>;
@group(1) @binding(3) var history_sampler: sampler;
@group(1) @binding(7) var out_tex: texture_storage_2d<rgba16float, write>;

struct TaaFrame {
    current_weight: f32,
    _pad0: f32,
    _pad1: vec2<f32>,
}

@group(1) @binding(9) var<storage, read_write> taa: TaaFrame;

fn to_ycocg(c: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(
        0.25 * c.r + 0.5 * c.g + 0.25 * c.b,
        0.5 * c.r - 0.5 * c.b,
        -0.25 * c.r + 0.5 * c.g - 0.25 * c.b,
    );
}

fn from_ycocg(c: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(c.x + c.y - c.z, c.x + c.z, c.x - c.y - c.z);
}

// The pixel's colour in YCoCg, with its alpha (the coverage a transparent background
// keeps).
fn load_ycocg(pixel: vec2<i32>) -> vec4<f32> {
    let c = textureLoad(current_tex, pixel, 0);
    return vec4<f32>(to_ycocg(c.rgb), c.a);
}

@compute @workgroup_size(8, 8)
fn cs_taa(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(out_tex);
    if any(id.xy >= size) {
        return;
    }
    let pixel = vec2<i32>(id.xy);
    let last = vec2<i32>(size) - 1;
    let current = load_ycocg(pixel);
    var low = current;
    var high = current;
    for (var dy = -1; dy <= 1; dy++) {
        for (var dx = -1; dx <= 1; dx++) {
            let c = load_ycocg(clamp(pixel + vec2<i32>(dx, dy), vec2<i32>(0), last));
            low = min(low, c);
            high = max(high, c);
        }
    }
    let motion = textureLoad(motion_tex, pixel, 0).xy;
    let previous = (vec2<f32>(pixel) + 0.5 - motion) / vec2<f32>(size);
    var weight = taa.current_weight;
    if any(previous < vec2<f32>(0.0)) || any(previous > vec2<f32>(1.0)) {
        weight = 1.0;
    }
    let h = textureSampleLevel(history_tex, history_sampler, previous, 0.0);
    let history = clamp(vec4<f32>(to_ycocg(h.rgb), h.a), low, high);
    let blended = mix(history, current, weight);
    textureStore(out_tex, pixel, vec4<f32>(from_ycocg(blended.xyz), blended.w));
}
