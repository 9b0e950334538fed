// Counts the distinct surfaces among a pixel's G-buffer samples: covered samples (view
// depth above 0) are clustered greedily, a sample joining the first cluster whose first
// sample has a normal within NORMAL_COS and a view depth within DEPTH_RELATIVE of its
// own. Red gets the count / 255 (exact in rgba8unorm); 0 where no sample is covered.

@group(0) @binding(0) var normal_tex: texture_multisampled_2d<f32>;
@group(0) @binding(1) var depth_tex: texture_multisampled_2d<f32>;

const NORMAL_COS: f32 = 0.95;
const DEPTH_RELATIVE: f32 = 0.01;
const MAX_SAMPLES: u32 = 16u;

// The G-buffer's octahedral normal encoding, undone.
fn oct_decode(e: vec2<f32>) -> vec3<f32> {
    var n = vec3<f32>(e, 1.0 - abs(e.x) - abs(e.y));
    let t = max(-n.z, 0.0);
    n.x += select(t, -t, n.x >= 0.0);
    n.y += select(t, -t, n.y >= 0.0);
    return normalize(n);
}

@fragment
fn fs_main(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let texel = vec2<u32>(position.xy);
    let samples = min(textureNumSamples(depth_tex), MAX_SAMPLES);
    var normals: array<vec3<f32>, 16>;
    var depths: array<f32, 16>;
    var clusters = 0u;
    for (var s = 0u; s < samples; s++) {
        let depth = textureLoad(depth_tex, texel, i32(s)).r;
        if depth <= 0.0 {
            continue;
        }
        let normal = oct_decode(textureLoad(normal_tex, texel, i32(s)).xy);
        var joined = false;
        for (var c = 0u; c < clusters; c++) {
            let near = abs(depth - depths[c]) <= DEPTH_RELATIVE * max(depth, depths[c]);
            if near && dot(normal, normals[c]) >= NORMAL_COS {
                joined = true;
                break;
            }
        }
        if !joined {
            normals[clusters] = normal;
            depths[clusters] = depth;
            clusters++;
        }
    }
    return vec4<f32>(f32(clusters) / 255.0, 0.0, 0.0, 1.0);
}
