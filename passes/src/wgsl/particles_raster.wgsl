// The particle pass in compute (passes/particles.rs, `stage: compute`): seed 001's
// off-screen particles without ROPs. A workgroup per TILE x TILE pixels of the off-screen
// targets, an invocation per pixel, walks the frame's particles in their blending order
// (the blended ones farthest first, then the emissive ones: gpu_scene/particles.rs) a
// chunk at a time: each invocation sets one particle up (its billboard on the targets,
// as vs_particle places it) and tests it against the tile, the chunk's hits are packed
// in order into workgroup memory (a prefix sum), and every invocation blends them over
// its pixel in registers: colour by conventional alpha blending over black, the
// transmittance multiplied by 1 - a, emissive light added, exactly the blend states of
// the fragment pass's off-screen targets, then stores both once. The fragment pass
// pays the ROPs for every blended fragment, hundreds deep in a column of smoke (13 ms
// for builtin:smoke's 112 million at 1920x1080 on the H200: docs/design/particles.md, run particles-scale2).
//
// A billboard faces the camera: its corners lie at one view depth, so on screen it is a
// rectangle whose `corner` coordinates are affine in the pixel position, which the
// fragment pass interpolates (perspective-correct, with one w for all four corners) and
// this computes from the pixel centre. Both keep a particle whose centre lies between
// the depth planes, whole (its corners share its clip depth).
//
// Composed after common.wgsl, scene.wgsl, particles.wgsl and the generated block binding
// the scene's view depth at the targets' size (group 1 binding 0, `scene_view_depth`);
// the targets are group 1 bindings 1 and 2, the particles group 2.

@group(1) @binding(1) var color_out: texture_storage_2d<rgba16float, write>;
@group(1) @binding(2) var additive_out: texture_storage_2d<rgba16float, write>;

const THREADS: u32 = TILE * TILE;

// A particle set up for a tile: its billboard's centre on the targets in pixels and the
// change of `corner` per pixel (x, y), its colour (lit albedo, or radiance) and opacity,
// its view depth, and whether it emits (added) rather than blends.
struct Splat {
    place: vec4<f32>,
    color: vec4<f32>,
    depth: f32,
    emissive: u32,
}

var<workgroup> splats: array<Splat, THREADS>;
// Per invocation of the chunk, how many of the chunk's particles up to its own hit the
// tile: an inclusive prefix sum.
var<workgroup> hits: array<u32, THREADS>;

// `p` projected to pixels of targets `size`, and whether it lies between the depth
// planes, in front of the camera.
fn on_targets(p: vec3<f32>, size: vec2<f32>) -> vec3<f32> {
    let clip = camera.view_proj * vec4<f32>(p, 1.0);
    let ndc = clip.xyz / clip.w;
    let between = clip.w > 0.0 && ndc.z >= 0.0 && ndc.z <= 1.0;
    return vec3<f32>((ndc.x * 0.5 + 0.5) * size.x, (0.5 - ndc.y * 0.5) * size.y, f32(between));
}

// Particle `i` set up: whether its billboard may cover a pixel centre of the tile whose
// first and last pixel centres are `low` and `high`.
struct SetUp {
    splat: Splat,
    hit: bool,
}

fn set_up(i: u32, axes: BillboardAxes, size: vec2<f32>, low: vec2<f32>, high: vec2<f32>) -> SetUp {
    let p = particles[i];
    let half = 0.5 * p.size;
    let centre = on_targets(p.position, size);
    let right = on_targets(p.position + axes.right * half, size).xy - centre.xy;
    let up = on_targets(p.position + axes.up * half, size).xy - centre.xy;
    // Screen-aligned (the axes are the camera's), up is negative y.
    let extent = vec2<f32>(abs(right.x), abs(up.y));
    let emissive = i >= particle_counts.blended;
    var color = lit_albedo(p.color);
    if emissive {
        color = p.color;
    }
    let view_depth = dot(p.position, camera.forward);
    let splat = Splat(
        vec4<f32>(centre.xy, 1.0 / right.x, 1.0 / up.y),
        vec4<f32>(color, p.alpha),
        view_depth,
        u32(emissive),
    );
    let hit = centre.z > 0.0 && all(extent > vec2<f32>(0.0))
        && all(centre.xy + extent >= low) && all(centre.xy - extent <= high);
    return SetUp(splat, hit);
}

@compute @workgroup_size(TILE, TILE, 1)
fn cs_particles(
    @builtin(workgroup_id) tile: vec3<u32>,
    @builtin(local_invocation_id) local_id: vec3<u32>,
    @builtin(local_invocation_index) local: u32,
) {
    let dims = textureDimensions(color_out);
    let size = vec2<f32>(dims);
    let origin = tile.xy * TILE;
    let pixel = origin + local_id.xy;
    let inside = all(pixel < dims);
    let low = vec2<f32>(origin) + 0.5;
    let high = low + f32(TILE - 1u);
    let at = vec2<f32>(pixel) + 0.5;
    var scene_depth = 0.0;
    if inside {
        scene_depth = scene_view_depth(vec2<i32>(pixel));
    }
    let axes = billboard_axes();
    let count = particle_counts.total;
    // Blended over black, transmittance 1; emissive light added.
    var color = vec3<f32>(0.0);
    var transmittance = 1.0;
    var added = vec3<f32>(0.0);
    for (var first = 0u; first < count; first += THREADS) {
        let i = first + local;
        var setup: SetUp;
        if i < count {
            setup = set_up(i, axes, size, low, high);
        }
        hits[local] = u32(setup.hit);
        workgroupBarrier();
        for (var d = 1u; d < THREADS; d <<= 1u) {
            var before = 0u;
            if local >= d {
                before = hits[local - d];
            }
            workgroupBarrier();
            hits[local] += before;
            workgroupBarrier();
        }
        if setup.hit {
            splats[hits[local] - 1u] = setup.splat;
        }
        let packed = workgroupUniformLoad(&hits[THREADS - 1u]);
        for (var j = 0u; j < packed && inside; j++) {
            let s = splats[j];
            let corner = (at - s.place.xy) * s.place.zw;
            if dot(corner, corner) >= 1.0 {
                continue;
            }
            let a = particle_opacity(corner, s.color.a, s.depth, scene_depth);
            if s.emissive != 0u {
                added += emitted_light(s.color.rgb, a);
            } else {
                color = s.color.rgb * a + color * (1.0 - a);
                transmittance *= 1.0 - a;
            }
        }
        workgroupBarrier();
    }
    if inside {
        textureStore(color_out, pixel, vec4<f32>(color, transmittance));
        textureStore(additive_out, pixel, vec4<f32>(added, 0.0));
    }
}
