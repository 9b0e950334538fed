// A tile's keys covered in one workgroup, an invocation per pixel (the tile raster of
// Laine and Karras, "High-Performance Software Rasterization on GPUs", HPG 2011): the
// tile's triangles, binned by bin_triangles.wgsl, are set up RASTER_CHUNK at a time, one per
// invocation (a binned triangle read from the bins' records, a spanning piece, a
// triangle of a cluster listed whole or a piece of a spanning cluster's set up here and
// tested against the tile, and the tile's blocks it may cover found), then each
// invocation tests its pixel's samples against each triangle that may cover its block, as
// the lanes of one vector, keeping the nearest key of each sample in registers
// (triangle_setup.wgsl's keys: the order the triangles come in does not matter). A warp
// is a block of 4 x 8 pixels: on the H200 at 3840x2160 this took builtin:dense's raster
// from 1.02 to 0.81 ms at 4x and from 0.76 to 0.68 at 1x, with the strict inside test
// in cover_lanes (docs/design/compute-raster.md, run visibility-blocks).
//
// Group 1 binds the draws, the bins and the clusters at bindings 1 to 9 and 12
// (common/gpu/tile_bins.rs), group
// 3 the texture table, which textured alpha masks read. Composed after common.wgsl,
// scene.wgsl, geometry.wgsl, material.wgsl, material_table.wgsl, plane_hit.wgsl,
// mask_texture.wgsl and triangle_setup.wgsl, with a
// generated block defining TILE and the sample lanes (LaneF, LaneU, LaneB, LANES,
// LANE_GROUPS, LANE_X, LANE_Y and `lane`, which the Rust side's sample_lanes writes).

@group(1) @binding(1) var<storage, read> draws: array<RasterDraw>;
@group(1) @binding(2) var<storage, read> tile_ends: array<u32>;
@group(1) @binding(3) var<storage, read> tile_starts: array<u32>;
@group(1) @binding(4) var<storage, read> tile_entries: array<u32>;
@group(1) @binding(5) var<storage, read> spanning: array<u32>;
// bin_triangles.wgsl's BinCounts, read after it is done: its first two counts.
struct SpanningCounts {
    pieces: u32,
    clusters: u32,
}
@group(1) @binding(6) var<storage, read> spanning_counts: SpanningCounts;
@group(1) @binding(7) var<storage, read> spanning_triangles: array<Spanning>;
@group(1) @binding(8) var<storage, read> records: array<ScreenTriangle>;
@group(1) @binding(9) var<storage, read> clusters: array<RasterCluster>;
@group(1) @binding(12) var<storage, read> spanning_clusters: array<Spanning>;

// Triangles set up a chunk at a time, one per invocation, then tested by every invocation.
const RASTER_CHUNK: u32 = min(TILE * TILE, 64u);
// The chunks a cluster listed whole takes: one, but for tiles of fewer than 8 x 8 pixels
// (rgraph_scene::CLUSTER_TRIANGLES is 64).
const CLUSTER_CHUNKS: u32 = (64u + RASTER_CHUNK - 1u) / RASTER_CHUNK;
// The chunks a spanning cluster takes: every piece of each triangle (a clipped one's fan
// has up to 3).
const SPANNING_CLUSTER_CHUNKS: u32 = (3u * 64u + RASTER_CHUNK - 1u) / RASTER_CHUNK;

var<workgroup> chunk: array<CoverTriangle, RASTER_CHUNK>;
// The tile's blocks each may cover (blocks_touched).
var<workgroup> chunk_blocks: array<u32, RASTER_CHUNK>;
var<workgroup> chunk_count: atomic<u32>;
// Of RASTER_CHUNK spanning clusters, those whose bounds meet the tile's (clusters_met).
var<workgroup> met: array<u32, RASTER_CHUNK>;
var<workgroup> met_count: atomic<u32>;
var<workgroup> met_total: u32;

// Whether pixel bounds `a` and `b` (min and max corners, inclusive) overlap.
fn overlap(a: vec4<i32>, b: vec4<i32>) -> bool {
    return all(max(a.xy, b.xy) <= min(a.zw, b.zw));
}

// Piece `k` of the t-th triangle set up (the whole triangle is piece 0 of an unclipped
// one; pieces its fan does not have have area 0), with area 0 where it misses the tile's
// pixels `tile` (min and max corners, inclusive).
fn piece_in_tile(t: u32, k: u32, tile: vec4<i32>) -> ScreenTriangle {
    var screen: ScreenTriangle;
    let triangle = clip_triangle(t);
    if unclipped(triangle) {
        if k == 0u {
            screen = whole_triangle(triangle);
        }
    } else if k < clipped_count(triangle) {
        screen = clipped_triangle(triangle, k);
    }
    if !overlap(pixel_bounds(screen), tile) {
        screen.area = 0.0;
    }
    return screen;
}

// Entry `i` of the tile's list (its binned triangles, then the spanning pieces), set up,
// with area 0 where it misses the tile's pixels `tile`. A tile whose list did not fit
// (`complete` false) takes every piece of every triangle instead.
fn chunk_triangle(i: u32, binned: u32, start: u32, tile: vec4<i32>, complete: bool) -> ScreenTriangle {
    if !complete {
        return piece_in_tile(i / 3u, i % 3u, tile);
    }
    if i < binned {
        return records[tile_entries[start + i]];
    }
    let piece = spanning[i - binned];
    let triangle = spanning_triangles[piece >> 2u];
    if !overlap(spanning_pixels(triangle), tile) {
        return ScreenTriangle();
    }
    return piece_in_tile(triangle.index, piece & 3u, tile);
}

// A triangle set up for covering: its three edge functions (b -> c, c -> a, a -> b:
// triangle_setup.wgsl's edge_at) as planes, each its value at an anchor, the pixel
// corner at or before the edge's lesser corner, and its changes per pixel right and down,
// so that a pixel takes two multiply-adds per edge and a sample two more. The triangle
// sharing an edge has the same anchor and exactly the negated value and changes (edge_at's
// value is exactly negated, the changes are differences of the same corners), so its
// function is exactly negated at every sample: no gaps, no double cover; and nothing
// depends on the tile. The clip depth is corner a's plus the other two corners'
// differences from it weighted by their edge functions over the area (`depth`), exact to
// the triangle's own depth range however thin it is. Bits 0 to 2 of `owns` say which
// edges own the samples on them (owned_edges), bit 3 (MASK_TEXTURED) that its alpha mask
// reads a texture; `mask` and `inverse_w` are the alpha mask's (mask_passes).
struct CoverTriangle {
    at_anchor: vec3<f32>,
    id: u32,
    anchor_x: vec3<f32>,
    owns: u32,
    anchor_y: vec3<f32>,
    per_x: vec3<f32>,
    per_y: vec3<f32>,
    depth: vec3<f32>,
    mask: vec4<f32>,
    inverse_w: vec3<f32>,
}

fn cover_triangle(t: ScreenTriangle) -> CoverTriangle {
    let corners = array<vec2<f32>, 3>(t.a.xy, t.b.xy, t.c.xy);
    var c: CoverTriangle;
    for (var k = 0u; k < 3u; k++) {
        let u = corners[(k + 1u) % 3u];
        let v = corners[(k + 2u) % 3u];
        let anchor = floor(select(v, u, lesser_first(u, v)));
        c.at_anchor[k] = edge_at(u, v, anchor);
        c.anchor_x[k] = anchor.x;
        c.anchor_y[k] = anchor.y;
        c.per_x[k] = u.y - v.y;
        c.per_y[k] = v.x - u.x;
    }
    c.depth = vec3<f32>(t.a.z, (t.b.z - t.a.z) / t.area, (t.c.z - t.a.z) / t.area);
    c.mask = t.mask;
    c.inverse_w = vec3<f32>(t.a.w, t.b.w, t.c.w);
    c.id = t.id;
    let owns = owned_edges(t);
    c.owns = u32(owns.x) | (u32(owns.y) << 1u) | (u32(owns.z) << 2u);
    if MASK_TEXTURES && t.mask.w >= 0.0 && mask_textured(meshes[mesh_of_triangle(t.id - 1u)].material) {
        c.owns |= MASK_TEXTURED;
    }
    return c;
}

// CoverTriangle's `owns` bit: the alpha mask reads the base colour texture.
const MASK_TEXTURED: u32 = 8u;

// The three edge functions of `t` at the top-left corner of `pixel`.
fn edges_at_pixel(t: CoverTriangle, pixel: vec2<u32>) -> vec3<f32> {
    let p = vec2<f32>(pixel);
    return t.at_anchor + t.per_x * (p.x - t.anchor_x) + t.per_y * (p.y - t.anchor_y);
}

// Inside edge `k`, or on it where it owns the samples on it (triangle_setup.wgsl).
fn inside_lanes(w: LaneF, owns: u32, k: u32) -> LaneB {
    return (w > LaneF(0.0)) | ((w == LaneF(0.0)) & LaneB(((owns >> k) & 1u) != 0u));
}

// The alpha mask (triangle_setup.wgsl's mask_of) tested at the centre of `pixel`, whose
// corner has edge functions `corner`, where the hardware pass's fragment reads it, inside
// the triangle or not: the pixel's samples are kept or dropped together, as a discard
// drops them. Alpha is interpolated perspective-correct (alpha / w and 1 / w are linear in
// screen space); the edge functions are the barycentrics times the area, which both sides
// of the test share. A textured mask multiplies in the base colour texel's alpha there
// (mask_texture.wgsl), as the hardware pass does.
fn mask_passes(t: CoverTriangle, corner: vec3<f32>, pixel: vec2<u32>) -> bool {
    if t.mask.w < 0.0 {
        return true;
    }
    let l = corner + 0.5 * (t.per_x + t.per_y);
    var alpha = dot(l, t.mask.xyz);
    if MASK_TEXTURES && (t.owns & MASK_TEXTURED) != 0u {
        alpha *= mask_texel_alpha(t.id, vec2<f32>(pixel) + 0.5);
    }
    return alpha >= t.mask.w * dot(l, t.inverse_w);
}

// Keeps the nearer of `t`'s keys and `depths`' and `ids`' in each sample of the pixel
// whose corner has edge functions `corner`: a sample inside all three edges, at a depth
// within [0, 1], takes `t` where its depth is nearer, or equal and its ID larger.
fn cover_lanes(corner: vec3<f32>, t: CoverTriangle, depths: ptr<function, array<LaneU, LANE_GROUPS>>, ids: ptr<function, array<LaneU, LANE_GROUPS>>) {
    let id = LaneU(t.id);
    for (var g = 0u; g < LANE_GROUPS; g++) {
        let x = LANE_X[g];
        let y = LANE_Y[g];
        let w0 = LaneF(corner.x) + t.per_x.x * x + t.per_y.x * y;
        let w1 = LaneF(corner.y) + t.per_x.y * x + t.per_y.y * y;
        let w2 = LaneF(corner.z) + t.per_x.z * x + t.per_y.z * y;
        let depth = LaneF(t.depth.x) + w1 * t.depth.y + w2 * t.depth.z;
        // Inside all three edges: strictly, or on an edge that owns the sample. A sample
        // exactly on an edge is rare, so the owners are asked only then: the strict test
        // is two minimums and a compare a sample (at 4x most of the raster's cost over 1x
        // is such per-sample arithmetic).
        let nearest_edge = min(min(w0, w1), w2);
        var inside = nearest_edge > LaneF(0.0);
        if any(nearest_edge == LaneF(0.0)) {
            inside = inside_lanes(w0, t.owns, 0u) & inside_lanes(w1, t.owns, 1u) & inside_lanes(w2, t.owns, 2u);
        }
        let covered = inside & (depth >= LaneF(0.0)) & (depth <= LaneF(1.0));
        // A covered depth is not negative, but may be -0, whose sign bit would order it
        // above every depth.
        let bits = bitcast<LaneU>(depth) & LaneU(0x7fffffffu);
        let kept = (*depths)[g];
        let nearer = covered & ((bits > kept) | ((bits == kept) & (id > (*ids)[g])));
        (*depths)[g] = select(kept, bits, nearer);
        (*ids)[g] = select((*ids)[g], id, nearer);
    }
}

// A pixel's keys, each sample's depth bits and ID as a lane.
struct TileKeys {
    depths: array<LaneU, LANE_GROUPS>,
    ids: array<LaneU, LANE_GROUPS>,
}

// Sample `s`'s key in `keys`, ID low (x), depth high (y).
fn key_of_sample(keys: TileKeys, s: u32) -> vec2<u32> {
    let g = s / LANES;
    return vec2<u32>(lane(keys.ids[g], s % LANES), lane(keys.depths[g], s % LANES));
}

// The tile in blocks of BLOCK_W x BLOCK_H pixels, a warp of 32 invocations to a block (a
// bit each in blocks_touched's masks): a warp runs a triangle's tests when any of its
// pixels may be covered, and a block taller than wide meets fewer of the tall thin
// triangles (grass, poles) than two rows of 16 pixels. Tiles that are not a multiple of
// a side take it whole.
const BLOCK_W: u32 = select(TILE, 4u, TILE % 4u == 0u);
const BLOCK_H: u32 = select(TILE, 8u, TILE % 8u == 0u);
const BLOCKS_ACROSS: u32 = TILE / BLOCK_W;
const BLOCKS: u32 = BLOCKS_ACROSS * (TILE / BLOCK_H);

// The block of the tile's invocation `local`: consecutive invocations fill a block.
fn block_of(local: u32) -> u32 {
    return local / (BLOCK_W * BLOCK_H);
}

// The top-left pixel of block `b` in its tile, the blocks row by row.
fn block_corner(b: u32) -> vec2<u32> {
    return vec2<u32>(b % BLOCKS_ACROSS * BLOCK_W, b / BLOCKS_ACROSS * BLOCK_H);
}

// The pixel of the tile invocation `local` covers: its block's, row by row.
fn pixel_in_tile(local: u32) -> vec2<u32> {
    let within = local % (BLOCK_W * BLOCK_H);
    return block_corner(block_of(local)) + vec2<u32>(within % BLOCK_W, within / BLOCK_W);
}

// The blocks of the tile at `origin` that `t`, whose pixel bounds are `bounds`, may cover
// a sample of: those its bounds meet and whose samples its edges do not all leave. An
// edge leaves a block where its largest value there (at the block's corner, plus its
// rises right and down) is below zero by more than the rounding of any sample's value
// there: a few ulps of the terms it sums at the tile's far corner from the edge's anchor
// (2^-18 of them is 32), so no sample a skipped block holds could have been inside. Set
// up once per triangle and tile, so that a warp skips a triangle whose bounds take in its
// pixels but whose area misses them, as a thin leaning one's mostly does, with one test.
fn blocks_touched(t: CoverTriangle, bounds: vec4<i32>, origin: vec2<u32>) -> u32 {
    let size = vec2<f32>(f32(BLOCK_W), f32(BLOCK_H));
    let rise = max(t.per_x, vec3<f32>(0.0)) * size.x + max(t.per_y, vec3<f32>(0.0)) * size.y;
    let o = vec2<f32>(origin);
    let far_x = max(abs(o.x - t.anchor_x), abs(o.x + f32(TILE) - t.anchor_x));
    let far_y = max(abs(o.y - t.anchor_y), abs(o.y + f32(TILE) - t.anchor_y));
    let terms = abs(t.at_anchor) + abs(t.per_x) * far_x + abs(t.per_y) * far_y;
    let least = -terms * 0x1p-18f - rise;
    let at_origin = edges_at_pixel(t, origin);
    var touched = 0u;
    for (var b = 0u; b < BLOCKS; b++) {
        let offset = block_corner(b);
        let block = origin + offset;
        let pixels = vec4<i32>(vec2<i32>(block), vec2<i32>(block + vec2<u32>(BLOCK_W - 1u, BLOCK_H - 1u)));
        let corner = at_origin + t.per_x * f32(offset.x) + t.per_y * f32(offset.y);
        if overlap(pixels, bounds) && all(corner >= least) {
            touched |= 1u << b;
        }
    }
    return touched;
}

// Piece `p` of cluster `c`, whose triangles are taken `pieces` pieces each (1 for a
// cluster within the depth planes, whose triangles are whole; 3 for every piece of a
// clipped fan), set up, with area 0 where it misses the tile's pixels `tile` or the
// cluster has no such piece.
fn cluster_piece(c: RasterCluster, p: u32, pieces: u32, tile: vec4<i32>) -> ScreenTriangle {
    if p / pieces >= c.triangles {
        return ScreenTriangle();
    }
    return piece_in_tile(c.first + p / pieces, p % pieces, tile);
}

// Triangle `i` of the `k`-th chunk of the tile's whole clusters, listed from `start`
// (CLUSTER_CHUNKS chunks each), set up. A whole cluster lies within the depth planes.
fn cluster_triangle(k: u32, i: u32, start: u32, tile: vec4<i32>) -> ScreenTriangle {
    let c = clusters[tile_entries[start + k / CLUSTER_CHUNKS]];
    return cluster_piece(c, (k % CLUSTER_CHUNKS) * RASTER_CHUNK + i, 1u, tile);
}

// Piece `i` of the `k`-th chunk of the spanning clusters the tile met (clusters_met,
// SPANNING_CLUSTER_CHUNKS chunks each), set up: every piece, as a spanning cluster may
// cross a depth plane.
fn spanning_cluster_piece(k: u32, i: u32, tile: vec4<i32>) -> ScreenTriangle {
    let c = clusters[met[k / SPANNING_CLUSTER_CHUNKS]];
    return cluster_piece(c, (k % SPANNING_CLUSTER_CHUNKS) * RASTER_CHUNK + i, 3u, tile);
}

// Of the spanning clusters from `first` to `first + RASTER_CHUNK` (but not past `count`),
// those whose bounds meet the tile's pixels `tile` listed in `met` (the workgroup's
// invocations calling together, each with its `local` index), and how many: the same
// for every invocation.
fn clusters_met(first: u32, count: u32, tile: vec4<i32>, local: u32) -> u32 {
    if local == 0u {
        atomicStore(&met_count, 0u);
    }
    workgroupBarrier();
    if local < RASTER_CHUNK && first + local < count {
        let s = spanning_clusters[first + local];
        if overlap(spanning_pixels(s), tile) {
            met[atomicAdd(&met_count, 1u)] = s.index;
        }
    }
    workgroupBarrier();
    if local == 0u {
        met_total = atomicLoad(&met_count);
    }
    return workgroupUniformLoad(&met_total);
}

// Covers a chunk of triangles (the workgroup's invocations calling together, each with
// its `local` index and its triangle `t` to set up, area 0 for none) into the keys
// `depths` and `ids` of the invocation's pixel of the tile at `origin`: the triangles set
// up in workgroup memory, then each tested by the warps of the blocks it may cover.
fn cover_chunk(t: ScreenTriangle, origin: vec2<u32>, local: u32, depths: ptr<function, array<LaneU, LANE_GROUPS>>, ids: ptr<function, array<LaneU, LANE_GROUPS>>) {
    if local == 0u {
        atomicStore(&chunk_count, 0u);
    }
    workgroupBarrier();
    if t.area > 0.0 {
        let slot = atomicAdd(&chunk_count, 1u);
        let cover = cover_triangle(t);
        chunk[slot] = cover;
        chunk_blocks[slot] = blocks_touched(cover, pixel_bounds(t), origin);
    }
    workgroupBarrier();
    let count = atomicLoad(&chunk_count);
    let pixel = origin + pixel_in_tile(local);
    let covers = all(pixel < output_size());
    let block = 1u << block_of(local);
    for (var j = 0u; j < count && covers; j++) {
        if (chunk_blocks[j] & block) == 0u {
            continue;
        }
        let c = chunk[j];
        let corner = edges_at_pixel(c, pixel);
        if mask_passes(c, corner, pixel) {
            cover_lanes(corner, c, depths, ids);
        }
    }
    workgroupBarrier();
}

// Covers the tile at `origin` (the workgroup's, every invocation calling with its own
// `local` index): the keys of the invocation's pixel, all 0 outside the output.
fn cover_tile(origin: vec2<u32>, local: u32) -> TileKeys {
    var depths: array<LaneU, LANE_GROUPS>;
    var ids: array<LaneU, LANE_GROUPS>;
    let tile_index = (origin.y / TILE) * ((output_size().x + TILE - 1u) / TILE) + origin.x / TILE;
    let start = tile_starts[tile_index];
    let end = tile_ends[tile_index];
    let binned = end - start;
    // Its whole clusters' list follows every tile's triangle list.
    let cluster_index = arrayLength(&tile_starts) / 2u + tile_index;
    let cluster_start = tile_starts[cluster_index];
    let cluster_end = tile_ends[cluster_index];
    // A list past the entries (bin_triangles.wgsl never writes one): every triangle's
    // pieces, three slots per triangle, and no cluster.
    let entries = arrayLength(&tile_entries);
    let complete = end <= entries && start <= end && cluster_end <= entries && cluster_start <= cluster_end;
    let total = select(3u * triangle_count(), binned + spanning_counts.pieces, complete);
    let triangle_chunks = (total + RASTER_CHUNK - 1u) / RASTER_CHUNK;
    let chunks = triangle_chunks + select(0u, (cluster_end - cluster_start) * CLUSTER_CHUNKS, complete);
    let tile = vec4<i32>(vec2<i32>(origin), vec2<i32>(origin + TILE - 1u));
    for (var k = 0u; k < chunks; k++) {
        var t: ScreenTriangle;
        let i = k * RASTER_CHUNK + local;
        if local < RASTER_CHUNK && (k >= triangle_chunks || i < total) {
            if k < triangle_chunks {
                t = chunk_triangle(i, binned, start, tile, complete);
            } else {
                t = cluster_triangle(k - triangle_chunks, local, cluster_start, tile);
            }
        }
        cover_chunk(t, origin, local, &depths, &ids);
    }
    // The spanning clusters (whose slots overflowed), RASTER_CHUNK at a time: those whose
    // bounds meet the tile's, each piece of their triangles.
    let spanning_count = select(0u, min(spanning_counts.clusters, arrayLength(&spanning_clusters)), complete);
    for (var first = 0u; first < spanning_count; first += RASTER_CHUNK) {
        let chunks = clusters_met(first, spanning_count, tile, local) * SPANNING_CLUSTER_CHUNKS;
        for (var k = 0u; k < chunks; k++) {
            var t: ScreenTriangle;
            if local < RASTER_CHUNK {
                t = spanning_cluster_piece(k, local, tile);
            }
            cover_chunk(t, origin, local, &depths, &ids);
        }
    }
    return TileKeys(depths, ids);
}
