// Temporal anti-aliasing (passes/taa.rs): this frame's image, drawn with a jittered
// camera, blended into the previous frame's result reprojected by the motion vectors.
// The history is read where the pixel's surface was through a Catmull-Rom filter (five
// bilinear taps, Jimenez's "Filmic SMAA" 2016), which a moving image's history keeps
// sharper than bilinear reads that blur it a little more every frame; then it is clipped
// to the box this frame's 3 x 3 neighbourhood spans in YCoCg (Karis, "High quality
// temporal supersampling", 2014), narrowed to GAMMA standard deviations about its mean
// (Salvi's variance clipping), so what the history shows of a surface no longer there (a
// ghost) cannot outlast one frame where its colour lies outside that box; then this frame
// weighs `current_weight` (the pass sets it each frame: 1 after a reset, 1 / n for the
// n-th frame since, down to 1 - the history weight), or more where the image moves:
// `motion_weight` per pixel of motion (velocity-weighted feedback), since every frame's
// resampling of a moving history blurs it a little more and its clamped edges lag. The
// motion is the front-most surface's of the 3 x 3 neighbourhood (the least view depth,
// the motion texture's blue), so a silhouette's pixels, whose centre may see the surface
// behind, follow the edge that moves over them. Where the previous position is off screen
// the frame is taken alone; where the previous frame showed there a surface that moved
// across this pixel's point and hid it, the frame weighs at least the share of the
// history that shows it (`hidden_share`: the generated block after this file defines
// it, from a history of the motion, taa_disocclusion.wgsl, or 0 where the pass has
// none): that history shows what hid this pixel's surface, which the box of a shaded or
// textured surface's neighbourhood is too wide to clamp away. This frame's own pixel is read where the output pixel's centre
// lies in it (the camera's jitter moved the frame's image by `taa.jitter` pixels) through
// a Catmull-Rom filter: blended as it was drawn, the jittered sample would displace a
// moving image by the weighted mean of the last few frames' jitters (a still image's
// average over the cycle is the pixel's box, but in motion the few frames that weigh most
// sit off its centre). Composed after common.wgsl, before the block defining
// `hidden_share(previous, depth_before, slope, motion)`: the share of the history at
// pixel coordinate `previous` that shows a surface nearer than `depth_before` (the view
// depth the pixel's point had in the previous frame, on a surface whose view depth
// changes by `slope` a pixel) and moving otherwise than `motion`.

@group(1) @binding(0) var current_tex: texture_2d<f32>;
@group(1) @binding(1) var motion_tex: texture_2d<f32>;
@group(1) @binding(2) var history_tex: texture_2d<f32>;
@group(1) @binding(3) var history_sampler: sampler;
@group(1) @binding(7) var out_tex: texture_storage_2d<rgba16float, write>;

struct TaaFrame {
    current_weight: f32,
    motion_weight: f32,
    // This frame's camera offset, in pixels (x right, y down).
    jitter: vec2<f32>,
}

@group(1) @binding(9) var<storage, read_write> taa: TaaFrame;

const GAMMA: f32 = 1.25;

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

fn history_at(uv: vec2<f32>) -> vec4<f32> {
    return textureSampleLevel(history_tex, history_sampler, uv, 0.0);
}

// The Catmull-Rom weights, per axis, of the four texels about a point `f` (0 to 1) past
// the centre of the second.
fn catmull_rom_weights(f: vec2<f32>) -> array<vec2<f32>, 4> {
    return array<vec2<f32>, 4>(
        f * (-0.5 + f * (1.0 - 0.5 * f)),
        1.0 + f * f * (-2.5 + 1.5 * f),
        f * (0.5 + f * (2.0 - 1.5 * f)),
        f * f * (-0.5 + 0.5 * f),
    );
}

// The history at `uv` through a Catmull-Rom filter: its 4 x 4 taps as five bilinear reads
// (the corners, which weigh least, left out), normalised by the weights read. Its negative
// lobes may overshoot; the clamp that follows bounds it.
fn history_catmull_rom(uv: vec2<f32>, size: vec2<f32>) -> vec4<f32> {
    let position = uv * size;
    let centre = floor(position - 0.5) + 0.5;
    let w = catmull_rom_weights(position - centre);
    let w0 = w[0];
    let w3 = w[3];
    let w12 = w[1] + w[2];
    let t0 = (centre - 1.0) / size;
    let t3 = (centre + 2.0) / size;
    let t12 = (centre + w[2] / w12) / size;
    let weights = array<f32, 5>(w12.x * w0.y, w0.x * w12.y, w12.x * w12.y, w3.x * w12.y, w12.x * w3.y);
    let taps = array<vec2<f32>, 5>(
        vec2<f32>(t12.x, t0.y),
        vec2<f32>(t0.x, t12.y),
        t12,
        vec2<f32>(t3.x, t12.y),
        vec2<f32>(t12.x, t3.y),
    );
    var sum = vec4<f32>(0.0);
    var total = 0.0;
    for (var i = 0u; i < 5u; i++) {
        sum += history_at(taps[i]) * weights[i];
        total += weights[i];
    }
    return max(sum / total, vec4<f32>(0.0));
}

// This frame's colour where the output pixel's centre lies in it, in YCoCg with its alpha:
// `centre + jitter` among its pixels, through a Catmull-Rom filter (4 x 4 loads, edges
// clamped), its negative lobes' overshoot cut at 0.
fn current_unjittered(pixel: vec2<i32>) -> vec4<f32> {
    let last = vec2<i32>(textureDimensions(current_tex)) - 1;
    let position = vec2<f32>(pixel) + 0.5 + taa.jitter;
    let first = floor(position - 0.5);
    let w = catmull_rom_weights(position - (first + 0.5));
    var sum = vec4<f32>(0.0);
    for (var y = 0; y < 4; y++) {
        for (var x = 0; x < 4; x++) {
            let at = clamp(vec2<i32>(first) + vec2<i32>(x - 1, y - 1), vec2<i32>(0), last);
            sum += textureLoad(current_tex, at, 0) * (w[x].x * w[y].y);
        }
    }
    let c = max(sum, vec4<f32>(0.0));
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
    var sum = vec4<f32>(0.0);
    var squares = vec4<f32>(0.0);
    // x, y: motion in pixels; z: view depth; w: the point's view depth a frame before.
    var front = textureLoad(motion_tex, pixel, 0);
    // The neighbourhood's view depths, row by row.
    var depths: array<f32, 9>;
    for (var dy = -1; dy <= 1; dy++) {
        for (var dx = -1; dx <= 1; dx++) {
            let at = clamp(pixel + vec2<i32>(dx, dy), vec2<i32>(0), last);
            let m = textureLoad(motion_tex, at, 0);
            depths[(dy + 1) * 3 + dx + 1] = m.z;
            if m.z < front.z {
                front = m;
            }
            let c = load_ycocg(at);
            low = min(low, c);
            high = max(high, c);
            sum += c;
            squares += c * c;
        }
    }
    // Salvi's variance clipping: the box narrowed to GAMMA standard deviations about the
    // neighbourhood's mean, within its min and max.
    let mean = sum / 9.0;
    let deviation = sqrt(max(squares / 9.0 - mean * mean, vec4<f32>(0.0)));
    low = max(low, mean - GAMMA * deviation);
    high = min(high, mean + GAMMA * deviation);
    let motion = front.xy;
    let previous = (vec2<f32>(pixel) + 0.5 - motion) / vec2<f32>(size);
    var weight = max(taa.current_weight, min(length(motion) * taa.motion_weight, 1.0));
    // The pixel's surface's change of view depth per pixel, along x plus along y: the
    // lesser step to either side, so that a silhouette beside the pixel adds nothing.
    let d = depths[4];
    let slope = min(abs(depths[5] - d), abs(d - depths[3])) + min(abs(depths[7] - d), abs(d - depths[1]));
    let off_screen = any(previous < vec2<f32>(0.0)) || any(previous > vec2<f32>(1.0));
    if off_screen {
        weight = 1.0;
    }
    weight = max(weight, hidden_share(previous * vec2<f32>(size), front.w, slope, motion));
    let h = history_catmull_rom(previous, vec2<f32>(size));
    let history = clamp(vec4<f32>(to_ycocg(h.rgb), h.a), low, high);
    let blended = mix(history, current_unjittered(pixel), weight);
    textureStore(out_tex, pixel, vec4<f32>(from_ycocg(blended.xyz), blended.w));
}
