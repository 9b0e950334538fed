// The shadow maps' compute raster (passes/shadow_raster.rs): every opaque cluster of each
// view (gpu_scene/view_culling.rs), the nearest depth of each atlas texel kept by
// atomicMax of its bits inverted (0: nothing), which `shadow_resolve` writes into the
// atlas. Small clusters (wholly between the view's depth planes, each spanning a few
// texels) take an invocation a triangle; large ones a workgroup a chunk of triangles, its
// invocations sharing their rows' texels; a triangle of more than HUGE_CHUNK texels
// (a ground plane across a view) is handed on in chunks that workgroups across the GPU
// cover (cs_shadow_raster_huge), so that no workgroup covers a whole view alone. Each
// triangle's texels are those of its rows' spans (`row_span`), not its whole bounds: a
// thin diagonal triangle's bounds are mostly empty.
// Composed after common.wgsl, scene.wgsl, geometry.wgsl and shadow_views.wgsl.

// A run of `triangles` triangles of mesh `mesh` from index `first_index`, into view
// `view` (gpu_scene/shadow_work.rs's `RasterRuns`), and the first of its chunks (a
// workgroup's ITEM_TRIANGLES triangles each) in its dispatch: the small clusters' runs
// first, then the large ones', each dispatch's chunks counted from 0.
struct Run {
    view: u32,
    mesh: u32,
    first_index: u32,
    triangles: u32,
    first_chunk: u32,
}

struct RasterParams {
    // The atlas's side in texels.
    atlas: u32,
    // The hardware's slope-scaled depth bias (shadow_raster's slope_bias).
    slope_bias: f32,
    // The small clusters' runs, and the large ones' after them.
    small: u32,
    large: u32,
    // The chunks (workgroups) of the small and of the large dispatch.
    small_chunks: u32,
    large_chunks: u32,
}

// Triangles of a chunk: gpu_scene/shadow_work.rs's ITEM_TRIANGLES.
const ITEM_TRIANGLES: u32 = 64u;

// A workgroup's triangles: `count` (at most ITEM_TRIANGLES) triangles of mesh `mesh` from
// index `first_index`, into view `view`.
struct Item {
    view: u32,
    mesh: u32,
    first_index: u32,
    count: u32,
}

// The huge triangles handed on: their set-ups, and per chunk of HUGE_CHUNK texels the
// triangle's index and the chunk's (counts cleared with the keys).
struct HugeFlats {
    count: atomic<u32>,
    chunks: atomic<u32>,
    flats: array<Flat>,
}

@group(1) @binding(0) var<storage, read_write> shadow_keys: array<atomic<u32>>;
@group(1) @binding(1) var<storage, read> runs: array<Run>;
@group(1) @binding(2) var<storage, read> raster: RasterParams;
@group(1) @binding(3) var<storage, read_write> huge: HugeFlats;
@group(1) @binding(4) var<storage, read_write> huge_chunks: array<vec2<u32>>;

// Clears the keys: 256 a workgroup, the workgroups in rows of num_workgroups.x.
@compute @workgroup_size(256)
fn cs_clear(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = id.y * groups.x * 256u + id.x;
    if i < arrayLength(&shadow_keys) {
        atomicStore(&shadow_keys[i], 0u);
    }
    if i == 0u {
        atomicStore(&huge.count, 0u);
        atomicStore(&huge.chunks, 0u);
    }
}

// Chunk `chunk` of the dispatch over `count` runs from run `first`: in the last run whose
// first chunk is not past it (a binary search; a run of no triangles has no chunk).
fn item(first: u32, count: u32, chunk: u32) -> Item {
    var low = first;
    var high = first + count;
    while high - low > 1u {
        let middle = (low + high) / 2u;
        if runs[middle].first_chunk <= chunk {
            low = middle;
        } else {
            high = middle;
        }
    }
    let run = runs[low];
    let start = (chunk - run.first_chunk) * ITEM_TRIANGLES;
    return Item(run.view, run.mesh, run.first_index + 3u * start, min(run.triangles - start, ITEM_TRIANGLES));
}

// The signed area of the parallelogram of a -> b and a -> p: which side of edge a b the
// point p lies on.
fn edge(a: vec2<f32>, b: vec2<f32>, p: vec2<f32>) -> f32 {
    return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
}

// A triangle projected into a view's tile: corners in atlas texels (y down), their
// depths, the texels whose centres its bounds hold (within the tile; none where
// high < low), its signed area (0: nothing to draw) and the hardware's slope-scaled
// depth bias for its plane.
struct Flat {
    p0: vec2<f32>,
    p1: vec2<f32>,
    p2: vec2<f32>,
    low: vec2<f32>,
    high: vec2<f32>,
    z: vec3<f32>,
    area: f32,
    bias: f32,
}

// The triangle of clip-space corners `c` in view `view`'s tile. Its corners lie in front
// of the near plane (z >= 0, so w > 0): the caller clipped it.
fn flat(c: array<vec4<f32>, 3>, view: ShadowView) -> Flat {
    let atlas = f32(raster.atlas);
    let origin = view.rect.xy * atlas;
    let side = view.rect.zw * atlas;
    var f: Flat;
    var p: array<vec2<f32>, 3>;
    var z: array<f32, 3>;
    for (var i = 0u; i < 3u; i++) {
        let ndc = c[i].xyz / c[i].w;
        p[i] = origin + vec2<f32>(0.5 * ndc.x + 0.5, 0.5 - 0.5 * ndc.y) * side;
        z[i] = ndc.z;
    }
    f.p0 = p[0];
    f.p1 = p[1];
    f.p2 = p[2];
    f.z = vec3<f32>(z[0], z[1], z[2]);
    f.area = edge(p[0], p[1], p[2]);
    f.low = max(ceil(min(min(p[0], p[1]), p[2]) - 0.5), origin);
    f.high = min(floor(max(max(p[0], p[1]), p[2]) - 0.5), origin + side - 1.0);
    if f.area == 0.0 {
        return f;
    }
    // The depth's plane: its change per texel across and down, and the slope-scaled
    // bias the hardware adds (wgpu's DepthBiasState::slope_scale: the larger change).
    let d1 = vec3<f32>(p[1] - p[0], z[1] - z[0]);
    let d2 = vec3<f32>(p[2] - p[0], z[2] - z[0]);
    let dz_dx = (d1.z * d2.y - d2.z * d1.y) / f.area;
    let dz_dy = (d2.z * d1.x - d1.z * d2.x) / f.area;
    f.bias = raster.slope_bias * max(abs(dz_dx), abs(dz_dy));
    return f;
}

// Keeps `f`'s depth at texel (x, y) where the triangle holds its centre (edges included:
// a texel on an edge both triangles share gets either's depth, which is one) and the
// depth is not past the far plane, which clips it as the hardware does.
fn cover(f: Flat, x: f32, y: f32) {
    let centre = vec2<f32>(x + 0.5, y + 0.5);
    let w0 = edge(f.p1, f.p2, centre) / f.area;
    let w1 = edge(f.p2, f.p0, centre) / f.area;
    let w2 = edge(f.p0, f.p1, centre) / f.area;
    let depth = dot(vec3<f32>(w0, w1, w2), f.z);
    if min(min(w0, w1), w2) < 0.0 || depth > 1.0 {
        return;
    }
    let texel = u32(y) * raster.atlas + u32(x);
    atomicMax(&shadow_keys[texel], ~bitcast<u32>(clamp(depth + f.bias, 0.0, 1.0)));
}

// The columns of row `y` (first, last; none where last < first) holding every texel centre
// that `cover` may find inside `f`: its bounds' columns, narrowed by each edge that
// crosses the row's centre line where it does. The crossing is computed otherwise than
// `cover`'s edge functions, so it is widened by a texel plus far more than either's
// rounding (relative to the magnitudes involved, f32's 6e-8 an operation, some ten in
// sequence): `cover` still tests each texel, so the texels kept are those of the whole
// bounds, exactly.
fn row_span(f: Flat, y: f32) -> vec2<f32> {
    var first = f.low.x;
    var last = f.high.x;
    let centre = y + 0.5;
    let corners = array(f.p0, f.p1, f.p2);
    let reach = max(abs(f.low.x), abs(f.high.x) + 1.0);
    for (var i = 0u; i < 3u; i++) {
        let a = corners[i];
        let d = corners[(i + 1u) % 3u] - a;
        // Inside: the edge function (d.x (centre - a.y) - d.y (x - a.x)) has the area's
        // sign, so x lies on one side of a.x + along / d.y, which side by d.y's sign.
        let along = d.x * (centre - a.y);
        // A crossing this far off bounds nothing the bounds do not (and an edge along
        // the row crosses nowhere).
        if !(abs(along) < abs(d.y) * 1e7) {
            continue;
        }
        let crossing = a.x + along / d.y;
        let slack = 1.0 + 1e-5 * (abs(crossing) + abs(crossing - a.x) + abs(a.x) + reach);
        if (d.y > 0.0) == (f.area > 0.0) {
            last = min(last, floor(crossing + slack - 0.5));
        } else {
            first = max(first, ceil(crossing - slack - 0.5));
        }
    }
    return vec2<f32>(first, last);
}

// Corner `c` of triangle `t` of `item` in its view's clip space.
fn corner(item: Item, t: u32, c: u32, view: ShadowView) -> vec4<f32> {
    let mesh = meshes[item.mesh];
    let position = pull_position(item.first_index + 3u * t + c, mesh);
    return view.clip_from_world * (mesh.model * vec4<f32>(position, 1.0));
}

// Small clusters: an invocation a triangle, looping over the texels its bounds hold.
@compute @workgroup_size(64)
fn cs_shadow_raster(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lane: u32,
) {
    let k = group.y * groups.x + group.x;
    if k >= raster.small_chunks {
        return;
    }
    let item = item(0u, raster.small, k);
    if lane >= item.count {
        return;
    }
    let view = shadow_views.views[item.view];
    // The CPU kept only clusters wholly between the depth planes: nothing to clip.
    let f = flat(array(corner(item, lane, 0u, view), corner(item, lane, 1u, view), corner(item, lane, 2u, view)), view);
    if f.area == 0.0 {
        return;
    }
    for (var y = f.low.y; y <= f.high.y; y += 1.0) {
        let span = row_span(f, y);
        for (var x = span.x; x <= span.y; x += 1.0) {
            cover(f, x, y);
        }
    }
}

// Invocations of a large cluster's workgroup: they share each triangle's texels.
const LARGE_GROUP: u32 = 256u;
// Texels of a huge triangle's chunk: 16 a lane of a workgroup of LARGE_GROUP.
const HUGE_CHUNK: u32 = 4096u;

// A large chunk's triangles, set up once: triangle t's at 2t and 2t + 1 (clipping to the
// near plane leaves a triangle or a quadrilateral, two triangles).
var<workgroup> flats: array<Flat, FLATS>;
const FLATS: u32 = 2u * ITEM_TRIANGLES;
// Per flat, the first of the chunk's rows that are its own: the flats' rows in order,
// none for a flat handed on or of no area.
var<workgroup> first_row: array<u32, FLATS>;
// A prefix sum's running totals, one an invocation (`scan`).
var<workgroup> sums: array<u32, LARGE_GROUP>;
// A batch of LARGE_GROUP rows, one an invocation: its flat and row (`flat + FLATS * y`),
// and what a texel's index among the batch's texels adds to be its column.
var<workgroup> row_of: array<u32, LARGE_GROUP>;
var<workgroup> row_column: array<i32, LARGE_GROUP>;

// The inclusive prefix sum of `value` over the workgroup's invocations (Hillis and
// Steele), left in `sums`; called by every invocation, once whatever read `sums` before
// has passed a barrier.
fn scan(lane: u32, value: u32) -> u32 {
    sums[lane] = value;
    workgroupBarrier();
    for (var step = 1u; step < LARGE_GROUP; step <<= 1u) {
        var add = 0u;
        if lane >= step {
            add = sums[lane - step];
        }
        workgroupBarrier();
        sums[lane] += add;
        workgroupBarrier();
    }
    return sums[lane];
}

// Large clusters: a workgroup a chunk. Each of its first invocations clips one triangle
// to the near plane and projects it; then the chunk's rows are taken LARGE_GROUP at a
// time, an invocation a row finding its row's span, and the batch's texels shared out
// evenly, each invocation finding its texel's row by a binary search of their prefix
// sum: every invocation covers texels, whatever the triangles' shapes.
@compute @workgroup_size(256)
fn cs_shadow_raster_large(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lane: u32,
) {
    let k = group.y * groups.x + group.x;
    // The dispatch's last row may run past the chunks: those groups set up nothing and
    // cover nothing, but reach the barriers as the others do.
    let item = item(raster.small, raster.large, min(k, raster.large_chunks - 1u));
    let count = select(0u, item.count, k < raster.large_chunks);
    let view = shadow_views.views[item.view];
    if lane < ITEM_TRIANGLES {
        var none: Flat;
        flats[2u * lane] = none;
        flats[2u * lane + 1u] = none;
        if lane < count {
            set_up(item, lane, view);
        }
    }
    workgroupBarrier();
    // Each huge triangle is handed on by the invocation of its flat, all at once; a
    // huge triangle the buffers had no room for is covered here, more slowly.
    var rows = 0u;
    if lane < 2u * count {
        let f = flats[lane];
        let texels = texels_of(f);
        let handed = texels > HUGE_CHUNK && hand_on(f, texels);
        if !handed && texels > 0u && f.area != 0.0 {
            rows = u32(f.high.y - f.low.y) + 1u;
        }
    }
    let rows_to = scan(lane, rows);
    if lane < FLATS {
        first_row[lane] = rows_to - rows;
    }
    let total = workgroupUniformLoad(&sums[LARGE_GROUP - 1u]);
    for (var batch = 0u; batch < total; batch += LARGE_GROUP) {
        let r = batch + lane;
        var columns = 0u;
        if r < total {
            let t = flat_of_row(r);
            let f = flats[t];
            let y = f.low.y + f32(r - first_row[t]);
            let span = row_span(f, y);
            if span.y >= span.x {
                columns = u32(span.y - span.x) + 1u;
            }
            row_of[lane] = t + FLATS * u32(y);
            row_column[lane] = i32(span.x);
        }
        let texels_to = scan(lane, columns);
        row_column[lane] -= i32(texels_to - columns);
        workgroupBarrier();
        for (var i = lane; i < sums[LARGE_GROUP - 1u]; i += LARGE_GROUP) {
            let j = row_of_texel(i);
            let t = row_of[j] % FLATS;
            cover(flats[t], f32(row_column[j] + i32(i)), f32(row_of[j] / FLATS));
        }
        // The next batch's rows and sums replace these.
        workgroupBarrier();
    }
}

// The flat whose rows hold the chunk's row `r` (fewer than the rows' total): the last
// whose first row is not past it (a flat of no rows shares its first with the next).
fn flat_of_row(r: u32) -> u32 {
    var low = 0u;
    var high = FLATS;
    while high - low > 1u {
        let middle = (low + high) / 2u;
        if first_row[middle] <= r {
            low = middle;
        } else {
            high = middle;
        }
    }
    return low;
}

// The row of the batch whose texels hold the batch's texel `i` (fewer than their total):
// the first whose running total passes it.
fn row_of_texel(i: u32) -> u32 {
    var low = 0u;
    var high = LARGE_GROUP - 1u;
    while low < high {
        let middle = (low + high) / 2u;
        if sums[middle] > i {
            high = middle;
        } else {
            low = middle + 1u;
        }
    }
    return low;
}

// The texels whose centres `f`'s bounds hold (0 where none do).
fn texels_of(f: Flat) -> u32 {
    if any(f.high < f.low) {
        return 0u;
    }
    return (u32(f.high.x - f.low.x) + 1u) * (u32(f.high.y - f.low.y) + 1u);
}

// Hands huge triangle `f`, of `texels` texels in its bounds, on to cs_shadow_raster_huge
// in chunks; false where the buffers have no room for it. Every chunk reserved within the
// buffer is written, pointing nowhere where the triangle has no room, so that the huge
// pass reads no chunk of an earlier frame.
fn hand_on(f: Flat, texels: u32) -> bool {
    let chunks = (texels + HUGE_CHUNK - 1u) / HUGE_CHUNK;
    let first = atomicAdd(&huge.chunks, chunks);
    let room = arrayLength(&huge_chunks);
    var index = NOWHERE;
    if first + chunks <= room {
        let reserved = atomicAdd(&huge.count, 1u);
        if reserved < arrayLength(&huge.flats) {
            huge.flats[reserved] = f;
            index = reserved;
        }
    }
    for (var k = first; k < min(first + chunks, room); k++) {
        huge_chunks[k] = vec2<u32>(index, k - first);
    }
    return index != NOWHERE;
}

// A chunk of no triangle.
const NOWHERE: u32 = 0xffffffffu;

// Huge triangles' chunks: a workgroup a chunk, the workgroups of the dispatch taking
// every (number of workgroups)-th chunk from their own.
@compute @workgroup_size(256)
fn cs_shadow_raster_huge(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lane: u32,
) {
    let chunks = min(atomicLoad(&huge.chunks), arrayLength(&huge_chunks));
    let stride = groups.x * groups.y;
    for (var k = group.y * groups.x + group.x; k < chunks; k += stride) {
        let chunk = huge_chunks[k];
        if chunk.x == NOWHERE {
            continue;
        }
        let f = huge.flats[chunk.x];
        let width = u32(f.high.x - f.low.x) + 1u;
        let end = min(texels_of(f), (chunk.y + 1u) * HUGE_CHUNK);
        for (var i = chunk.y * HUGE_CHUNK + lane; i < end; i += LARGE_GROUP) {
            cover(f, f.low.x + f32(i % width), f.low.y + f32(i / width));
        }
    }
}

// Triangle `t` of `item` clipped to the near plane (z >= 0; Sutherland and Hodgman's
// polygon clipping against that one plane) and projected, into flats 2t and 2t + 1.
fn set_up(item: Item, t: u32, view: ShadowView) {
    var c: array<vec4<f32>, 3>;
    for (var i = 0u; i < 3u; i++) {
        c[i] = corner(item, t, i, view);
    }
    var polygon: array<vec4<f32>, 4>;
    var n = 0u;
    for (var i = 0u; i < 3u; i++) {
        let a = c[i];
        let b = c[(i + 1u) % 3u];
        if a.z >= 0.0 {
            polygon[n] = a;
            n++;
        }
        if (a.z >= 0.0) != (b.z >= 0.0) {
            polygon[n] = mix(a, b, a.z / (a.z - b.z));
            n++;
        }
    }
    if n >= 3u {
        flats[2u * t] = flat(array(polygon[0], polygon[1], polygon[2]), view);
    }
    if n == 4u {
        flats[2u * t + 1u] = flat(array(polygon[0], polygon[2], polygon[3]), view);
    }
}
