// The opaque draws' triangles binned to the tiled shading pass's tiles
// (common/gpu/tile_bins.rs), so that each tile's workgroup covers its own triangles in
// workgroup memory (visibility_tiles.wgsl) and no visibility buffer is written: the
// design of Laine and Karras's software rasteriser ("High-Performance Software
// Rasterization on GPUs", HPG 2011: bin, then rasterise tile by tile on chip).
//
// A triangle whose pixel bounds touch at most BINNED_TILES tiles is binned: listed in
// each of those tiles. The rest (large ones, and the pieces of those clipped against a
// depth plane) go to one list of "spanning" triangles that every tile reads, testing
// their bounds against its own. Four dispatches, in order:
// 1. cs_bins_clear: every tile's count to 0, the spanning list emptied.
// 2. cs_bins_count: per triangle, its tiles' counts raised, or it is added to the
//    spanning list (as `t << 2 | k`: piece k of the t-th triangle of all draws).
// 3. cs_bins_offsets: one workgroup turns the counts into each tile's first entry
//    (`tile_starts`, an exclusive prefix sum) and sets `tile_ends` there.
// 4. cs_bins_fill: per triangle again, its entry appended to each of its tiles by
//    raising `tile_ends`, which ends at the tile's last entry + 1.
// A tile's entries are in no particular order: coverage keeps the largest key, which
// does not depend on it. No list overflows: a binned triangle takes at most
// BINNED_TILES entries and a triangle at most 3 spanning pieces, and the buffers are
// sized for the scene's triangles.
//
// Composed after common.wgsl, scene.wgsl, geometry.wgsl and triangle_setup.wgsl.

@group(1) @binding(0) var<storage, read> draws: array<RasterDraw>;
@group(1) @binding(1) var<storage, read_write> tile_ends: array<atomic<u32>>;
@group(1) @binding(2) var<storage, read_write> tile_starts: array<u32>;
@group(1) @binding(3) var<storage, read_write> tile_entries: array<u32>;
@group(1) @binding(4) var<storage, read_write> spanning: array<u32>;
@group(1) @binding(5) var<storage, read_write> spanning_count: atomic<u32>;

// The shading pass's tile side in pixels.
override TILE: u32;
// common/gpu/tile_bins.rs sizes the entries by it.
override BINNED_TILES: u32;
const BIN_GROUP: u32 = 64u;
const SCAN_GROUP: u32 = 256u;

var<workgroup> scan: array<u32, SCAN_GROUP>;

fn invocation(id: vec3<u32>, groups: vec3<u32>) -> u32 {
    return id.x + id.y * groups.x * BIN_GROUP;
}

@compute @workgroup_size(64)
fn cs_bins_clear(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = invocation(id, groups);
    if i == 0u {
        atomicStore(&spanning_count, 0u);
    }
    if i < arrayLength(&tile_ends) {
        atomicStore(&tile_ends[i], 0u);
    }
}

// The `t`-th triangle as binned: `binned` with its tile bounds (min and max corners,
// inclusive), or not when it covers nothing or spans.
struct Binned {
    tiles: vec4<u32>,
    binned: bool,
}

// The t-th triangle's tiles; a spanning triangle's pieces are added to the spanning list
// when `list_spanning` (the count pass lists them, the fill pass skips them).
fn bin(t: u32, list_spanning: bool) -> Binned {
    var out = Binned(vec4<u32>(1u, 1u, 0u, 0u), false);
    let triangle = clip_triangle(t);
    var pieces = 1u;
    if unclipped(triangle) {
        let screen = whole_triangle(triangle);
        let bounds = pixel_bounds(screen);
        if screen.area == 0.0 || any(bounds.zw < bounds.xy) {
            return out;
        }
        let tiles = vec4<u32>(bounds) / TILE;
        let extent = tiles.zw - tiles.xy + 1u;
        if extent.x * extent.y <= BINNED_TILES {
            out.tiles = tiles;
            out.binned = true;
            return out;
        }
    } else {
        pieces = clipped_count(triangle);
    }
    if list_spanning && pieces > 0u {
        let first = atomicAdd(&spanning_count, pieces);
        for (var k = 0u; k < pieces; k++) {
            if first + k < arrayLength(&spanning) {
                spanning[first + k] = (t << 2u) | k;
            }
        }
    }
    return out;
}

fn tiles_across() -> u32 {
    return (output_size().x + TILE - 1u) / TILE;
}

@compute @workgroup_size(64)
fn cs_bins_count(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let t = invocation(id, groups);
    if t >= triangle_count() {
        return;
    }
    let b = bin(t, true);
    if !b.binned {
        return;
    }
    for (var y = b.tiles.y; y <= b.tiles.w; y++) {
        for (var x = b.tiles.x; x <= b.tiles.z; x++) {
            atomicAdd(&tile_ends[y * tiles_across() + x], 1u);
        }
    }
}

@compute @workgroup_size(256)
fn cs_bins_offsets(@builtin(local_invocation_index) local: u32) {
    let tiles = arrayLength(&tile_starts);
    let per = (tiles + SCAN_GROUP - 1u) / SCAN_GROUP;
    let first = local * per;
    let last = min(first + per, tiles);
    var sum = 0u;
    for (var i = first; i < last; i++) {
        sum += atomicLoad(&tile_ends[i]);
    }
    scan[local] = sum;
    workgroupBarrier();
    // Inclusive prefix sum of the invocations' sums (Hillis and Steele).
    for (var step = 1u; step < SCAN_GROUP; step <<= 1u) {
        var add = 0u;
        if local >= step {
            add = scan[local - step];
        }
        workgroupBarrier();
        scan[local] += add;
        workgroupBarrier();
    }
    var start = scan[local] - sum;
    for (var i = first; i < last; i++) {
        let count = atomicLoad(&tile_ends[i]);
        tile_starts[i] = start;
        atomicStore(&tile_ends[i], start);
        start += count;
    }
}

@compute @workgroup_size(64)
fn cs_bins_fill(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let t = invocation(id, groups);
    if t >= triangle_count() {
        return;
    }
    let b = bin(t, false);
    if !b.binned {
        return;
    }
    for (var y = b.tiles.y; y <= b.tiles.w; y++) {
        for (var x = b.tiles.x; x <= b.tiles.z; x++) {
            let entry = atomicAdd(&tile_ends[y * tiles_across() + x], 1u);
            if entry < arrayLength(&tile_entries) {
                tile_entries[entry] = t;
            }
        }
    }
}
