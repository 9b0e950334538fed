// The opaque draws' triangles set up for coverage in compute, as bin_triangles.wgsl bins them
// to tiles and tile_raster.wgsl covers a tile's: each transformed, clipped against the
// depth planes, projected to pixels and wound to a positive area, then tested sample by
// sample.
//
// Coverage follows the hardware's rules: a sample is inside when it is inside all
// three edges, and a sample exactly on an edge belongs to the triangle for which that
// edge is a top or left edge (D3D's rule), each edge evaluated the same way from both
// triangles sharing it (edge_at), so shared edges have no gaps and no double cover.
// Depth is the clip depth interpolated at the sample, affine in screen space. A sample
// keeps the nearest triangle as one 64-bit key, its reversed-Z depth's bits over the
// triangle's ID + 1, so that the largest key wins (a reversed-Z depth is a positive
// float, whose bits order as its values; equal depths keep the larger ID); 0, below
// every key, is "nothing drawn" at the far depth 0 (tile_raster.wgsl's cover_lanes).
//
// Composed after common.wgsl (SAMPLES, SAMPLE_POSITIONS), scene.wgsl and geometry.wgsl;
// the file composing it binds `draws`.

// A draw as the rasterisers see it: `triangles` triangles from `first_triangle` (the
// scene index buffer's position / 3) of mesh `mesh`, with `flags` CULL_BACK (back faces are
// dropped) and MASKED (alpha MASK: a pixel whose alpha is below the material's cutoff
// keeps none of its samples); `start` the number of triangles of the draws before it.
struct RasterDraw {
    first_triangle: u32,
    triangles: u32,
    start: u32,
    mesh: u32,
    flags: u32,
}

const CULL_BACK: u32 = 1u;
const MASKED: u32 = 2u;

// A cluster of a draw's triangles (rgraph_scene::Cluster, common/gpu/raster_draws.rs):
// `triangles` triangles from the `first`-th of all draws, of draw `draw`, its box
// (`min`, `max`), sphere (`center`, `radius`) and normal cone (`cone_axis`,
// `cone_cutoff`) in the mesh's object space.
struct RasterCluster {
    first: u32,
    triangles: u32,
    draw: u32,
    _pad: u32,
    min: vec3<f32>,
    cone_cutoff: f32,
    max: vec3<f32>,
    radius: f32,
    center: vec3<f32>,
    cone_axis: vec3<f32>,
}

// A triangle as coverage takes it: screen-space corners (x, y in pixels, clip depth,
// 1 / w) wound so that `area` is positive, its alpha mask (mask_of) and its ID + 1. An
// `area` of 0: it covers no sample (edge-on, culled, or not finite).
struct ScreenTriangle {
    a: vec4<f32>,
    b: vec4<f32>,
    c: vec4<f32>,
    mask: vec4<f32>,
    area: f32,
    id: u32,
}

// A triangle of the draws in clip space, before clipping: its corners, their alphas and
// the cutoff they are tested against (negative: no test), its ID + 1 and whether its back
// faces are culled.
struct ClipTriangle {
    corners: array<vec4<f32>, 3>,
    alpha: vec3<f32>,
    cutoff: f32,
    id: u32,
    cull: bool,
}

fn output_size() -> vec2<u32> {
    return vec2<u32>(camera.viewport);
}

// Pixel or tile coordinates (under 2^16 each, as every output is) packed in one word,
// x | y << 16: the bins' items and spanning entries hold them so.
fn pack(v: vec2<u32>) -> u32 {
    return v.x | (v.y << 16u);
}

fn unpack(v: u32) -> vec2<u32> {
    return vec2<u32>(v & 0xffffu, v >> 16u);
}

// A triangle or a cluster every tile reads (bin_triangles.wgsl's spanning lists): the
// triangle's `t` or the cluster's index, and pixel bounds that hold its pixels (min and
// max corners, inclusive, each packed), which a tile tests against its own first.
struct Spanning {
    index: u32,
    low: u32,
    high: u32,
}

fn spanning_pixels(s: Spanning) -> vec4<i32> {
    return vec4<i32>(vec2<i32>(unpack(s.low)), vec2<i32>(unpack(s.high)));
}

// Edge function of u -> v at p: positive on its right in pixel coordinates (y down),
// where a triangle of positive area has its inside.
fn edge(u: vec2<f32>, v: vec2<f32>, p: vec2<f32>) -> f32 {
    return (v.x - u.x) * (p.y - u.y) - (v.y - u.y) * (p.x - u.x);
}

// Whether corner `u` is an edge's lesser corner beside `v` (x first, then y): both
// triangles sharing the edge pick the same one.
fn lesser_first(u: vec2<f32>, v: vec2<f32>) -> bool {
    return u.x < v.x || (u.x == v.x && u.y < v.y);
}

// The edge function of u -> v, computed from the lesser corner so that the triangle on
// the other side, which walks v -> u, gets exactly its negation.
fn edge_at(u: vec2<f32>, v: vec2<f32>, p: vec2<f32>) -> f32 {
    if lesser_first(u, v) {
        return edge(u, v, p);
    }
    return -edge(v, u, p);
}

// Whether u -> v is a top edge (horizontal, walked to the right) or a left edge (walked
// up) of a triangle of positive area: those own the samples on them.
fn top_left(u: vec2<f32>, v: vec2<f32>) -> bool {
    let d = v - u;
    return d.y < 0.0 || (d.y == 0.0 && d.x > 0.0);
}

// Which of the triangle's edges (b -> c, c -> a, a -> b) own the samples on them.
fn owned_edges(t: ScreenTriangle) -> vec3<bool> {
    return vec3<bool>(top_left(t.b.xy, t.c.xy), top_left(t.c.xy, t.a.xy), top_left(t.a.xy, t.b.xy));
}

// The pixels whose samples may lie in the triangle, clamped to the output: min and max
// corners, inclusive; empty when max < min.
fn pixel_bounds(t: ScreenTriangle) -> vec4<i32> {
    let size = vec2<f32>(output_size());
    let low = clamp(floor(min(min(t.a.xy, t.b.xy), t.c.xy)), vec2<f32>(0.0), size);
    let high = clamp(floor(max(max(t.a.xy, t.b.xy), t.c.xy)), vec2<f32>(-1.0), size - 1.0);
    return vec4<i32>(vec2<i32>(low), vec2<i32>(high));
}

// A clip-space corner in pixels (x, y), clip depth and 1 / w.
fn to_screen(clip: vec4<f32>) -> vec4<f32> {
    let ndc = clip.xyz / clip.w;
    let size = camera.viewport;
    return vec4<f32>((ndc.x * 0.5 + 0.5) * size.x, (0.5 - ndc.y * 0.5) * size.y, ndc.z, 1.0 / clip.w);
}

// The alpha mask of the triangle with clip-space corners `a`, `b`, `c` and alphas
// `alpha` under `cutoff`: the corners' alpha over w, and the cutoff (negative: no test;
// tile_raster.wgsl's mask_passes tests it).
fn mask_of(a: vec4<f32>, b: vec4<f32>, c: vec4<f32>, alpha: vec3<f32>, cutoff: f32) -> vec4<f32> {
    return vec4<f32>(alpha / vec3<f32>(a.w, b.w, c.w), cutoff);
}

// The screen triangle of clip-space corners `a`, `b`, `c` with `mask`, wound to a
// positive area; area 0 when it covers nothing or is a culled back face (clockwise in
// NDC).
fn screen_triangle(ca: vec4<f32>, cb: vec4<f32>, cc: vec4<f32>, alpha: vec3<f32>, cutoff: f32, id: u32, cull: bool) -> ScreenTriangle {
    var t = ScreenTriangle(to_screen(ca), to_screen(cb), to_screen(cc), mask_of(ca, cb, cc, alpha, cutoff), 0.0, id);
    let area = edge(t.a.xy, t.b.xy, t.c.xy);
    // Edge-on, or not finite (a corner on the camera plane after clipping): no samples.
    // Counter-clockwise in NDC (y up), the front, is negative here (y down).
    if !(abs(area) > 0.0 && abs(area) < 1e30) || (area > 0.0 && cull) {
        return t;
    }
    t.area = abs(area);
    if area < 0.0 {
        let b = t.b;
        t.b = t.c;
        t.c = b;
        t.mask = t.mask.xzyw;
    }
    return t;
}

// Signed distances to the clip volume's depth planes, positive inside: z >= 0 and
// z <= w (WebGPU's 0 <= z <= w).
fn depth_planes(clip: vec4<f32>) -> vec2<f32> {
    return vec2<f32>(clip.z, clip.w - clip.z);
}

// The draw whose triangles include the `t`-th of all draws.
fn draw_of(t: u32) -> u32 {
    var low = 0u;
    var high = arrayLength(&draws);
    while high - low > 1u {
        let middle = (low + high) / 2u;
        if draws[middle].start <= t {
            low = middle;
        } else {
            high = middle;
        }
    }
    return low;
}

// The triangles of all the draws.
fn triangle_count() -> u32 {
    let last = draws[arrayLength(&draws) - 1u];
    return last.start + last.triangles;
}

// The `t`-th triangle of all draws, transformed to clip space.
fn clip_triangle(t: u32) -> ClipTriangle {
    let draw = draws[draw_of(t)];
    let triangle = draw.first_triangle + t - draw.start;
    let mesh = meshes[draw.mesh];
    var out: ClipTriangle;
    out.id = triangle + 1u;
    out.cull = (draw.flags & CULL_BACK) != 0u;
    // Unmasked triangles skip the test (a negative cutoff); masked ones take their base
    // colour's alpha times each vertex colour's, as visibility.wgsl does.
    out.alpha = vec3<f32>(1.0);
    out.cutoff = -1.0;
    let masked = (draw.flags & MASKED) != 0u;
    if masked {
        out.cutoff = materials[mesh.material].alpha_cutoff;
    }
    for (var k = 0u; k < 3u; k++) {
        // A masked triangle's vertices are pulled whole, once, for their colour too.
        var position: vec3<f32>;
        if masked {
            let v = pull_vertex(3u * triangle + k, mesh);
            position = v.position;
            out.alpha[k] = materials[mesh.material].base_color.a * v.color.a;
        } else {
            position = pull_position(3u * triangle + k, mesh);
        }
        out.corners[k] = camera.view_proj * (mesh.model * vec4<f32>(position, 1.0));
    }
    return out;
}

// Whether the triangle lies within both depth planes, in front of the camera: it is
// covered whole (whole_triangle), else by the fan of its clipped polygon (clipped_count,
// clipped_triangle).
fn unclipped(t: ClipTriangle) -> bool {
    let d = min(min(depth_planes(t.corners[0]), depth_planes(t.corners[1])), depth_planes(t.corners[2]));
    return all(d >= vec2<f32>(0.0)) && min(min(t.corners[0].w, t.corners[1].w), t.corners[2].w) > 0.0;
}

fn whole_triangle(t: ClipTriangle) -> ScreenTriangle {
    return screen_triangle(t.corners[0], t.corners[1], t.corners[2], t.alpha, t.cutoff, t.id, t.cull);
}

// A triangle clipped against both depth planes (Sutherland-Hodgman: at most five
// corners, alpha interpolated with them).
struct Clipped {
    corners: array<vec4<f32>, 5>,
    alphas: array<f32, 5>,
    count: u32,
}

fn clip_polygon(t: ClipTriangle) -> Clipped {
    var polygon = Clipped(array<vec4<f32>, 5>(t.corners[0], t.corners[1], t.corners[2], t.corners[0], t.corners[0]), array<f32, 5>(t.alpha.x, t.alpha.y, t.alpha.z, 0.0, 0.0), 3u);
    // Wholly outside one plane: nothing.
    let d = max(max(depth_planes(t.corners[0]), depth_planes(t.corners[1])), depth_planes(t.corners[2]));
    if any(d < vec2<f32>(0.0)) {
        polygon.count = 0u;
        return polygon;
    }
    for (var plane = 0u; plane < 2u; plane++) {
        var clipped: Clipped;
        var kept = 0u;
        for (var i = 0u; i < polygon.count; i++) {
            let next = (i + 1u) % polygon.count;
            let p = polygon.corners[i];
            let q = polygon.corners[next];
            let dp = depth_planes(p)[plane];
            let dq = depth_planes(q)[plane];
            if dp >= 0.0 && kept < 5u {
                clipped.corners[kept] = p;
                clipped.alphas[kept] = polygon.alphas[i];
                kept++;
            }
            if (dp >= 0.0) != (dq >= 0.0) && kept < 5u {
                let s = dp / (dp - dq);
                clipped.corners[kept] = mix(p, q, s);
                clipped.alphas[kept] = mix(polygon.alphas[i], polygon.alphas[next], s);
                kept++;
            }
        }
        clipped.count = kept;
        polygon = clipped;
        if kept < 3u {
            polygon.count = 0u;
            return polygon;
        }
    }
    return polygon;
}

// The triangles of a clipped triangle's fan (0 to 3).
fn clipped_count(t: ClipTriangle) -> u32 {
    return max(clip_polygon(t).count, 2u) - 2u;
}

// Triangle `k` of a clipped triangle's fan.
fn clipped_triangle(t: ClipTriangle, k: u32) -> ScreenTriangle {
    let p = clip_polygon(t);
    let alpha = vec3<f32>(p.alphas[0], p.alphas[k + 1u], p.alphas[k + 2u]);
    return screen_triangle(p.corners[0], p.corners[k + 1u], p.corners[k + 2u], alpha, t.cutoff, t.id, t.cull);
}
