// The visibility buffer rasterised in compute (passes/visibility_compute.rs): every
// sample keeps the nearest triangle as one 64-bit key, its reversed-Z depth's bits over
// the triangle's ID + 1, so a single atomicMax is the depth test and the ID write
// together (no render targets, no ROPs: the cost of a multisampled raster pass on chips
// with few of them). 0, below every key, is "nothing drawn" at the far depth 0.
//
// Three dispatches, in order:
// 1. cs_clear: every key to 0, the work lists emptied.
// 2. cs_raster: one invocation per triangle of the opaque draws. It transforms and clips
//    the triangle (against the near and far planes, in clip space), then covers a small
//    one's samples itself; a larger one is split into blocks of 8 x 8 pixels, listed as
//    items of up to ITEM_BLOCKS blocks, so that the work of a floor covering the screen
//    spreads over the whole GPU.
// 3. cs_raster_items: a fixed grid of 8 x 8 workgroups takes the items in turn, an
//    invocation per pixel of a block.
//
// Coverage follows the hardware's rules: a sample is inside when it is inside all
// three edges, and a sample exactly on an edge belongs to the triangle for which that
// edge is a top or left edge (D3D's rule), each edge evaluated the same way from both
// triangles sharing it (edge_at), so shared edges have no gaps and no double cover.
// Depth is the clip depth interpolated at the sample, affine in screen space.
//
// Composed after common.wgsl (SAMPLES, SAMPLE_POSITIONS), scene.wgsl and geometry.wgsl.

// A draw as the raster pass sees it: `triangles` triangles from `first_triangle` (the
// scene index buffer's position / 3) of mesh `mesh`, with `flags` CULL (back faces are
// dropped) and MASKED (alpha MASK: a pixel whose alpha is below the material's cutoff
// keeps none of its samples); `start` the number of triangles of the draws before it.
struct RasterDraw {
    first_triangle: u32,
    triangles: u32,
    start: u32,
    mesh: u32,
    flags: u32,
}

const CULL: u32 = 1u;
const MASKED: u32 = 2u;

// A triangle too large for one invocation: its screen-space corners (x, y in pixels,
// clip depth, 1 / w), wound so that its area is positive, its alpha mask (mask_of) and
// its ID + 1.
struct Listed {
    a: vec4<f32>,
    b: vec4<f32>,
    c: vec4<f32>,
    mask: vec4<f32>,
    id: u32,
}

// The work lists' lengths.
struct Counts {
    listed: atomic<u32>,
    items: atomic<u32>,
}

@group(1) @binding(0) var<storage, read_write> keys: array<atomic<u64>>;
@group(1) @binding(1) var<storage, read> draws: array<RasterDraw>;
@group(1) @binding(2) var<storage, read_write> counts: Counts;
@group(1) @binding(3) var<storage, read_write> listed: array<Listed>;
// Items: a listed triangle and its first block (NO_ITEM: none).
@group(1) @binding(4) var<storage, read_write> items: array<vec2<u32>>;

// A triangle whose bounding box holds more pixels than this is listed.
const SMALL_PIXELS: u32 = 32u;
const BLOCK: u32 = 8u;
const ITEM_BLOCKS: u32 = 16u;
const NO_ITEM: u32 = 0xffffffffu;
// cs_raster's workgroup, and cs_raster_items' grid of workgroups.
const RASTER_GROUP: u32 = 64u;
override ITEM_GROUPS: u32 = 1024u;

fn output_size() -> vec2<u32> {
    return vec2<u32>(camera.viewport);
}

fn key_of(depth: f32, id: u32) -> u64 {
    return (u64(bitcast<u32>(depth)) << 32u) | u64(id);
}

@compute @workgroup_size(64)
fn cs_clear(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = id.x + id.y * groups.x * 64u;
    if i == 0u {
        atomicStore(&counts.listed, 0u);
        atomicStore(&counts.items, 0u);
    }
    if i < arrayLength(&keys) {
        // A min with 0 clears with the 64-bit operations every device with 64-bit
        // atomics has (loads and stores of them are a further feature).
        atomicMin(&keys[i], 0lu);
    }
}

// Edge function of u -> v at p: positive on its right in pixel coordinates (y down),
// where a triangle of positive area has its inside.
fn edge(u: vec2<f32>, v: vec2<f32>, p: vec2<f32>) -> f32 {
    return (v.x - u.x) * (p.y - u.y) - (v.y - u.y) * (p.x - u.x);
}

// The edge function of u -> v, computed from the lesser corner so that the triangle on
// the other side, which walks v -> u, gets exactly its negation.
fn edge_at(u: vec2<f32>, v: vec2<f32>, p: vec2<f32>) -> f32 {
    if u.x < v.x || (u.x == v.x && u.y < v.y) {
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

fn inside(w: f32, owns: bool) -> bool {
    return w > 0.0 || (w == 0.0 && owns);
}

// An alpha mask: the corners' alpha over w, and the cutoff (negative: no test). Alpha is
// interpolated perspective-correct (alpha / w and 1 / w are linear in screen space) at
// the pixel centre, where the hardware pass's fragment reads it, inside the triangle or
// not, and the pixel's samples are kept or dropped together, as a discard drops them.
fn mask_passes(pixel: vec2<u32>, a: vec4<f32>, b: vec4<f32>, c: vec4<f32>, mask: vec4<f32>, area: f32) -> bool {
    if mask.w < 0.0 {
        return true;
    }
    let p = vec2<f32>(pixel) + 0.5;
    let l = vec3<f32>(edge_at(b.xy, c.xy, p), edge_at(c.xy, a.xy, p), edge_at(a.xy, b.xy, p)) / area;
    return dot(l, mask.xyz) >= mask.w * dot(l, vec3<f32>(a.w, b.w, c.w));
}

// Tests every sample of `pixel` against the triangle (positive area `area`) and keeps
// the nearer key.
fn cover_pixel(pixel: vec2<u32>, a: vec4<f32>, b: vec4<f32>, c: vec4<f32>, mask: vec4<f32>, area: f32, id: u32) {
    if !mask_passes(pixel, a, b, c, mask, area) {
        return;
    }
    let owns = vec3<bool>(top_left(b.xy, c.xy), top_left(c.xy, a.xy), top_left(a.xy, b.xy));
    let base = (pixel.y * output_size().x + pixel.x) * SAMPLES;
    var positions = SAMPLE_POSITIONS;
    for (var s = 0u; s < SAMPLES; s++) {
        let p = vec2<f32>(pixel) + positions[s];
        let w0 = edge_at(b.xy, c.xy, p);
        let w1 = edge_at(c.xy, a.xy, p);
        let w2 = edge_at(a.xy, b.xy, p);
        if inside(w0, owns.x) && inside(w1, owns.y) && inside(w2, owns.z) {
            let depth = (w0 * a.z + w1 * b.z + w2 * c.z) / area;
            if depth >= 0.0 && depth <= 1.0 {
                atomicMax(&keys[base + s], key_of(depth, id));
            }
        }
    }
}

// The pixels whose samples may lie in the triangle, clamped to the output: min and max
// corners, inclusive; empty when max < min.
fn pixel_bounds(a: vec4<f32>, b: vec4<f32>, c: vec4<f32>) -> vec4<i32> {
    let size = vec2<f32>(output_size());
    let low = clamp(floor(min(min(a.xy, b.xy), c.xy)), vec2<f32>(0.0), size);
    let high = clamp(floor(max(max(a.xy, b.xy), c.xy)), vec2<f32>(-1.0), size - 1.0);
    return vec4<i32>(vec2<i32>(low), vec2<i32>(high));
}

// A screen-space triangle (to_screen's corners, `mask` as cover_pixel takes it): covered
// here when small, else listed with its items. `cull`: back faces (clockwise in NDC) are
// dropped.
fn raster_screen(a_in: vec4<f32>, b_in: vec4<f32>, c_in: vec4<f32>, mask_in: vec4<f32>, id: u32, cull: bool) {
    let a = a_in;
    var b = b_in;
    var c = c_in;
    var mask = mask_in;
    var area = edge(a.xy, b.xy, c.xy);
    // Edge-on, or not finite (a corner on the camera plane after clipping): no samples.
    if !(abs(area) > 0.0 && abs(area) < 1e30) {
        return;
    }
    // Counter-clockwise in NDC (y up), the front, is negative here (y down).
    if area > 0.0 && cull {
        return;
    }
    if area < 0.0 {
        let t = b;
        b = c;
        c = t;
        mask = mask.xzyw;
        area = -area;
    }
    let bounds = pixel_bounds(a, b, c);
    if any(bounds.zw < bounds.xy) {
        return;
    }
    let extent = vec2<u32>(bounds.zw - bounds.xy) + 1u;
    if extent.x * extent.y > SMALL_PIXELS {
        let blocks = (extent + BLOCK - 1u) / BLOCK;
        let count = blocks.x * blocks.y;
        let item_count = (count + ITEM_BLOCKS - 1u) / ITEM_BLOCKS;
        let slot = atomicAdd(&counts.listed, 1u);
        let first_item = atomicAdd(&counts.items, item_count);
        let fits = slot < arrayLength(&listed) && first_item + item_count <= arrayLength(&items);
        if fits {
            listed[slot] = Listed(a, b, c, mask, id);
        }
        // A list is full: the items this triangle took that fit are marked empty (other
        // triangles may have taken items after them, so the count stays), and it is
        // covered here, slowly but exactly.
        let end = min(first_item + item_count, arrayLength(&items));
        for (var i = first_item; i < end; i++) {
            items[i] = select(vec2<u32>(NO_ITEM, 0u), vec2<u32>(slot, (i - first_item) * ITEM_BLOCKS), fits);
        }
        if fits {
            return;
        }
    }
    for (var y = bounds.y; y <= bounds.w; y++) {
        for (var x = bounds.x; x <= bounds.z; x++) {
            cover_pixel(vec2<u32>(vec2<i32>(x, y)), a, b, c, mask, area, id);
        }
    }
}

// A clip-space corner in pixels (x, y), clip depth and 1 / w.
fn to_screen(clip: vec4<f32>) -> vec4<f32> {
    let ndc = clip.xyz / clip.w;
    let size = camera.viewport;
    return vec4<f32>((ndc.x * 0.5 + 0.5) * size.x, (0.5 - ndc.y * 0.5) * size.y, ndc.z, 1.0 / clip.w);
}

// The mask of the triangle with clip-space corners `a`, `b`, `c` and alphas `alpha`
// under `cutoff` (negative: none).
fn mask_of(a: vec4<f32>, b: vec4<f32>, c: vec4<f32>, alpha: vec3<f32>, cutoff: f32) -> vec4<f32> {
    return vec4<f32>(alpha / vec3<f32>(a.w, b.w, c.w), cutoff);
}

// Signed distances to the clip volume's depth planes, positive inside: z >= 0 and
// z <= w (WebGPU's 0 <= z <= w).
fn depth_planes(clip: vec4<f32>) -> vec2<f32> {
    return vec2<f32>(clip.z, clip.w - clip.z);
}

// Clips the triangle (clip-space corners and their alphas) against both depth planes
// (Sutherland-Hodgman: at most five corners, alpha interpolated with them) and
// rasterises the fan of what is left.
fn raster_clipped(c0: vec4<f32>, c1: vec4<f32>, c2: vec4<f32>, alpha: vec3<f32>, cutoff: f32, id: u32, cull: bool) {
    var polygon = array<vec4<f32>, 5>(c0, c1, c2, c0, c0);
    var alphas = array<f32, 5>(alpha.x, alpha.y, alpha.z, 0.0, 0.0);
    var count = 3u;
    for (var plane = 0u; plane < 2u; plane++) {
        var clipped: array<vec4<f32>, 5>;
        var clipped_alphas: array<f32, 5>;
        var kept = 0u;
        for (var i = 0u; i < count; i++) {
            let next = (i + 1u) % count;
            let p = polygon[i];
            let q = polygon[next];
            let dp = depth_planes(p)[plane];
            let dq = depth_planes(q)[plane];
            if dp >= 0.0 && kept < 5u {
                clipped[kept] = p;
                clipped_alphas[kept] = alphas[i];
                kept++;
            }
            if (dp >= 0.0) != (dq >= 0.0) && kept < 5u {
                let t = dp / (dp - dq);
                clipped[kept] = mix(p, q, t);
                clipped_alphas[kept] = mix(alphas[i], alphas[next], t);
                kept++;
            }
        }
        polygon = clipped;
        alphas = clipped_alphas;
        count = kept;
        if count < 3u {
            return;
        }
    }
    for (var i = 1u; i + 1u < count; i++) {
        let a = polygon[0];
        let b = polygon[i];
        let c = polygon[i + 1u];
        let mask = mask_of(a, b, c, vec3<f32>(alphas[0], alphas[i], alphas[i + 1u]), cutoff);
        raster_screen(to_screen(a), to_screen(b), to_screen(c), mask, id, cull);
    }
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

@compute @workgroup_size(64)
fn cs_raster(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let t = gid.x + gid.y * groups.x * RASTER_GROUP;
    let last = draws[arrayLength(&draws) - 1u];
    if t >= last.start + last.triangles {
        return;
    }
    let draw = draws[draw_of(t)];
    let triangle = draw.first_triangle + t - draw.start;
    let mesh = meshes[draw.mesh];
    var clip: array<vec4<f32>, 3>;
    // Unmasked triangles skip the test (a negative cutoff); masked ones take their base
    // colour's alpha times each vertex colour's, as visibility.wgsl does.
    var alpha = vec3<f32>(1.0);
    var cutoff = -1.0;
    let masked = (draw.flags & MASKED) != 0u;
    if masked {
        cutoff = materials[mesh.material].alpha_cutoff;
    }
    for (var k = 0u; k < 3u; k++) {
        // A masked triangle's vertices are pulled whole, once, for their colour too.
        var position: vec3<f32>;
        if masked {
            let v = pull_vertex(3u * triangle + k, mesh);
            position = v.position;
            alpha[k] = materials[mesh.material].base_color.a * v.color.a;
        } else {
            position = pull_position(3u * triangle + k, mesh);
        }
        clip[k] = camera.view_proj * (mesh.model * vec4<f32>(position, 1.0));
    }
    let cull = (draw.flags & CULL) != 0u;
    let d0 = depth_planes(clip[0]);
    let d1 = depth_planes(clip[1]);
    let d2 = depth_planes(clip[2]);
    if all(min(min(d0, d1), d2) >= vec2<f32>(0.0)) && min(min(clip[0].w, clip[1].w), clip[2].w) > 0.0 {
        let mask = mask_of(clip[0], clip[1], clip[2], alpha, cutoff);
        raster_screen(to_screen(clip[0]), to_screen(clip[1]), to_screen(clip[2]), mask, triangle + 1u, cull);
    } else if all(max(max(d0, d1), d2) >= vec2<f32>(0.0)) {
        raster_clipped(clip[0], clip[1], clip[2], alpha, cutoff, triangle + 1u, cull);
    }
}

@compute @workgroup_size(8, 8)
fn cs_raster_items(@builtin(workgroup_id) group: vec3<u32>, @builtin(local_invocation_id) local: vec3<u32>) {
    let item_count = min(atomicLoad(&counts.items), arrayLength(&items));
    for (var i = group.x; i < item_count; i += ITEM_GROUPS) {
        let item = items[i];
        if item.x == NO_ITEM {
            continue;
        }
        let triangle = listed[item.x];
        let a = triangle.a;
        let b = triangle.b;
        let c = triangle.c;
        let bounds = pixel_bounds(a, b, c);
        let extent = vec2<u32>(bounds.zw - bounds.xy) + 1u;
        let blocks = (extent + BLOCK - 1u) / BLOCK;
        let area = edge(a.xy, b.xy, c.xy);
        let last = min(item.y + ITEM_BLOCKS, blocks.x * blocks.y);
        for (var k = item.y; k < last; k++) {
            let at = vec2<u32>(k % blocks.x, k / blocks.x) * BLOCK + local.xy;
            if all(at < extent) {
                cover_pixel(vec2<u32>(bounds.xy) + at, a, b, c, triangle.mask, area, triangle.id);
            }
        }
    }
}
