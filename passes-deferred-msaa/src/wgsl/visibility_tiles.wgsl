// A visibility buffer that never leaves the chip: the tiled shading pass's workgroup
// covers its tile's triangles (binned by tile_bins.wgsl) in workgroup memory before it
// shades them, each invocation keeping its pixel's nearest keys (triangle_setup.wgsl's)
// in registers, then in `tile_keys`, where `sample_id` and `sample_depth` read them as
// visibility_samples.wgsl reads a compute rasteriser's buffer. The same coverage rules
// and keys as that rasteriser's, so the same image; no buffer of keys is written or read.
//
// Group 1 binds the draws and the bins at bindings 9 to 15. Composed after common.wgsl,
// scene.wgsl, geometry.wgsl and triangle_setup.wgsl, inside light_tiled.wgsl's generated
// block (TILE), before visibility_read.wgsl.

@group(1) @binding(9) var<storage, read> draws: array<RasterDraw>;
@group(1) @binding(10) var<storage, read> tile_ends: array<u32>;
@group(1) @binding(11) var<storage, read> tile_starts: array<u32>;
@group(1) @binding(12) var<storage, read> tile_entries: array<u32>;
@group(1) @binding(13) var<storage, read> spanning: array<u32>;
// tile_bins.wgsl's BinCounts, read after it is done: the spanning pieces first.
@group(1) @binding(14) var<storage, read> spanning_count: u32;
@group(1) @binding(15) var<storage, read> spanning_bounds: array<vec2<u32>>;
@group(1) @binding(16) var<storage, read> records: array<ScreenTriangle>;

// Triangles set up a chunk at a time, one per invocation, then tested by every invocation.
const RASTER_CHUNK: u32 = min(TILE * TILE, 64u);

// Each pixel's samples' keys (triangle_setup.wgsl's), at the pixel's index in the tile
// times SAMPLES plus the sample.
var<workgroup> tile_keys: array<vec2<u32>, TILE * TILE * SAMPLES>;
var<workgroup> chunk: array<ScreenTriangle, RASTER_CHUNK>;
// Their pixel bounds (pixel_bounds), which most of the tile's pixels are outside.
var<workgroup> chunk_bounds: array<vec4<i32>, RASTER_CHUNK>;
var<workgroup> chunk_count: atomic<u32>;

fn key_at(pixel: vec2<i32>, s: u32) -> vec2<u32> {
    let at = vec2<u32>(pixel) % TILE;
    return tile_keys[(at.y * TILE + at.x) * SAMPLES + s];
}

fn sample_id(pixel: vec2<i32>, s: u32) -> u32 {
    return key_at(pixel, s).x;
}

fn sample_depth(pixel: vec2<i32>, s: u32) -> f32 {
    return bitcast<f32>(key_at(pixel, s).y);
}

// Whether pixel bounds `a` and `b` (min and max corners, inclusive) overlap.
fn overlap(a: vec4<i32>, b: vec4<i32>) -> bool {
    return all(max(a.xy, b.xy) <= min(a.zw, b.zw));
}

// Entry `i` of the tile's list (its binned triangles, then the spanning pieces), set up,
// with area 0 where it misses the tile's pixels `tile` (min and max corners, inclusive).
fn chunk_triangle(i: u32, binned: u32, start: u32, tile: vec4<i32>) -> ScreenTriangle {
    if i < binned {
        return records[tile_entries[start + i]];
    }
    var t: ScreenTriangle;
    let piece = spanning[i - binned];
    let packed = spanning_bounds[piece >> 2u];
    let bounds = vec4<i32>(vec2<i32>(vec2<u32>(packed.x & 0xffffu, packed.x >> 16u)), vec2<i32>(vec2<u32>(packed.y & 0xffffu, packed.y >> 16u)));
    if !overlap(bounds, tile) {
        return t;
    }
    let triangle = clip_triangle(piece >> 2u);
    if unclipped(triangle) {
        t = whole_triangle(triangle);
    } else {
        t = clipped_triangle(triangle, piece & 3u);
    }
    if !overlap(pixel_bounds(t), tile) {
        t.area = 0.0;
    }
    return t;
}

// edge_at for lanes of sample positions `x`, `y`: the same operations, lane by lane.
fn edge_lanes(u: vec2<f32>, v: vec2<f32>, x: LaneF, y: LaneF) -> LaneF {
    if u.x < v.x || (u.x == v.x && u.y < v.y) {
        return (v.x - u.x) * (y - u.y) - (v.y - u.y) * (x - u.x);
    }
    return -((u.x - v.x) * (y - v.y) - (u.y - v.y) * (x - v.x));
}

fn inside_lanes(w: LaneF, owns: bool) -> LaneB {
    return (w > LaneF(0.0)) | ((w == LaneF(0.0)) & LaneB(owns));
}

// Keeps the nearer of `t`'s keys and `depths`' and `ids`' in each sample of `pixel`
// (triangle_setup.wgsl's sample_key and key_max, lane by lane).
fn cover_lanes(pixel: vec2<u32>, t: ScreenTriangle, depths: ptr<function, array<LaneU, LANE_GROUPS>>, ids: ptr<function, array<LaneU, LANE_GROUPS>>) {
    let owns = owned_edges(t);
    let id = LaneU(t.id);
    for (var g = 0u; g < LANE_GROUPS; g++) {
        let x = LaneF(f32(pixel.x)) + LANE_X[g];
        let y = LaneF(f32(pixel.y)) + LANE_Y[g];
        let w0 = edge_lanes(t.b.xy, t.c.xy, x, y);
        let w1 = edge_lanes(t.c.xy, t.a.xy, x, y);
        let w2 = edge_lanes(t.a.xy, t.b.xy, x, y);
        let depth = (w0 * t.a.z + w1 * t.b.z + w2 * t.c.z) / t.area;
        let covered = inside_lanes(w0, owns.x) & inside_lanes(w1, owns.y) & inside_lanes(w2, owns.z)
            & (depth >= LaneF(0.0)) & (depth <= LaneF(1.0));
        let bits = bitcast<LaneU>(depth);
        let kept = (*depths)[g];
        let nearer = covered & ((bits > kept) | ((bits == kept) & (id > (*ids)[g])));
        (*depths)[g] = select(kept, bits, nearer);
        (*ids)[g] = select((*ids)[g], id, nearer);
    }
}

// Covers the tile at `origin` (the workgroup's, every invocation calling with its own
// `local` index) and leaves its keys in tile_keys for after the next barrier.
fn raster_tile(origin: vec2<u32>, local: u32) {
    let tile_index = (origin.y / TILE) * ((output_size().x + TILE - 1u) / TILE) + origin.x / TILE;
    let start = tile_starts[tile_index];
    let binned = tile_ends[tile_index] - start;
    let total = binned + spanning_count;
    let tile = vec4<i32>(vec2<i32>(origin), vec2<i32>(origin + TILE - 1u));
    let pixel = origin + vec2<u32>(local % TILE, local / TILE);
    let covers = all(pixel < output_size());
    // Each sample's key as its depth's bits and its ID, a lane each.
    var depths: array<LaneU, LANE_GROUPS>;
    var ids: array<LaneU, LANE_GROUPS>;
    for (var first = 0u; first < total; first += RASTER_CHUNK) {
        if local == 0u {
            atomicStore(&chunk_count, 0u);
        }
        workgroupBarrier();
        if local < RASTER_CHUNK && first + local < total {
            let t = chunk_triangle(first + local, binned, start, tile);
            if t.area > 0.0 {
                let slot = atomicAdd(&chunk_count, 1u);
                chunk[slot] = t;
                chunk_bounds[slot] = pixel_bounds(t);
            }
        }
        workgroupBarrier();
        let count = atomicLoad(&chunk_count);
        let at = vec2<i32>(pixel);
        for (var j = 0u; j < count && covers; j++) {
            let bounds = chunk_bounds[j];
            if any(at < bounds.xy) || any(at > bounds.zw) {
                continue;
            }
            let t = chunk[j];
            if mask_passes(pixel, t) {
                cover_lanes(pixel, t, &depths, &ids);
            }
        }
        workgroupBarrier();
    }
    for (var s = 0u; s < SAMPLES; s++) {
        let g = s / LANES;
        tile_keys[local * SAMPLES + s] = vec2<u32>(lane(ids[g], s % LANES), lane(depths[g], s % LANES));
    }
}
