// The opaque draws' triangles binned to tiles (common/gpu/tile_bins.rs), so that each
// tile's workgroup covers its own triangles (tile_raster.wgsl): the design of Laine and
// Karras's software rasteriser ("High-Performance Software Rasterization on GPUs", HPG
// 2011: bin, then rasterise tile by tile on chip).
//
// The draws' triangles come in clusters (common/gpu/raster_draws.rs), each culled first
// (CULL_CLUSTERS): wholly outside a plane of the view volume by its box, or showing only
// back faces by its normal cone where its draw culls them and its mesh's transform keeps
// angles (a rotation, uniform scale and translation). A cluster that lies within the
// depth planes and whose box touches at most CLUSTER_TILES tiles is listed whole in each
// of those tiles' cluster lists (WHOLE_CLUSTERS): the tile sets its triangles up itself,
// and neither their records nor one count per triangle and tile are written. Binning per
// cluster is what keeps a dense mesh's binning cheap: at one triangle per pixel, a tile's
// count was raised by hundreds of triangles, each an atomic on the same word. Before
// that test, a cluster within the depth planes whose pixel bounds hold at most
// MICRO_PIXELS pixels per triangle is micro: listed in `micro` for micro_raster.wgsl, a
// triangle an invocation, and its tiles marked in `micro_tiles` (whose keys that pass
// clears and the tile raster merges with its own). Other clusters are binned by
// triangle, each into the bins' slots:
//
// The slots. The per-triangle arrays (`records`, `spanning_triangles`, and the entries'
// BINNED_TILES per triangle) hold as many triangles as common/gpu/bin_sizes.rs gives
// them, which the output's size bounds, not the scene's. A cluster binned by triangle
// takes its triangles' slots, numbered densely, by one atomic on `bin_counts.slots` (a
// prefix over the clusters binned so far), and is listed in `fallback` with its first
// slot. A cluster whose slots would run past the arrays overflows, and takes a path that
// needs none, as correct and slower: listed whole (as above) where it lies within the
// depth planes and touches at most CLUSTER_TILES tiles (the entries hold CLUSTER_TILES
// per cluster, whole or not), else added to `spanning_clusters`, which every tile reads,
// setting up each triangle of those whose pixel bounds meet its own (tile_raster.wgsl).
// Which clusters overflow depends on the order the atomics come in; the image does not,
// as each sample keeps the largest key of every triangle covering it, whichever way the
// triangle came.
//
// A binned triangle whose pixel bounds touch a tile is listed in that tile (`tile_entries`,
// by its slot), but for those clipped against a depth plane and those the entries have
// no room for: their pieces (`slot << 2 | k`, piece k of the clipped polygon's fan) go to
// one list of "spanning" pieces that every tile reads, testing the triangle's pixel
// bounds (`spanning_triangles`, which also holds its `t`) against its own first. A
// triangle touching at most BINNED_TILES tiles lists itself; a larger one takes room
// for its entries from what is left after BINNED_TILES per slot and CLUSTER_TILES per
// cluster, and is listed by items of up to ITEM_TILES tiles, an invocation per tile, so
// that a triangle across the screen spreads over the GPU.
//
// Each tile has two lists: its triangles (count and start at the tile's index) and its
// whole clusters (at the number of tiles plus the tile's index), both in `tile_entries`.
// Dispatches, in order:
// 1. cs_bins_clear: every list's count to 0, the other lists emptied.
// 2. cs_clusters_count: per cluster, culled, or its tiles' cluster counts raised, or
//    given slots and added to the fallback list, or, where its slots overflow, listed
//    whole or spanning; what became of it kept in `cluster_kinds`. With occlusion
//    culling (cluster_occlusion.wgsl), the first phase also lists those the previous
//    frame's pyramid hides, and the second phase takes the clusters listed rather than
//    every cluster (each phase's listed_cluster and occlusion_kind).
// 3. cs_clusters_args: the fallback list's workgroups, the indirect arguments of the
//    dispatches binning its triangles (`fallback_args`), then the micro list's, those of
//    micro_raster.wgsl's dispatch.
// 4. cs_bins_count: per triangle of a fallback cluster, its record written in its slot
//    and its tiles' counts raised (or its items listed, or its pieces added to the
//    spanning list).
// 5. cs_bins_count_items: the items' tiles' counts raised.
// 6. cs_bins_offsets: one workgroup turns the counts into each list's first entry
//    (`tile_starts`, an exclusive prefix sum) and sets `tile_ends` there.
// 7. cs_bins_fill, cs_bins_fill_items and cs_clusters_fill: each entry written by
//    raising `tile_ends`, which ends at the list's last entry + 1.
// A tile's entries are in no particular order: coverage keeps the largest key, which
// does not depend on it. No list overflows: the entries hold BINNED_TILES per slot,
// CLUSTER_TILES per cluster and the room large triangles take, the items at most one per
// BINNED_TILES of that room, the spanning list 3 pieces per slot, the spanning clusters
// one per cluster. (Should the room's count still overrun, a tile whose list ends past
// the entries walks every triangle instead: tile_raster.wgsl.)
//
// Composed after common.wgsl, scene.wgsl, geometry.wgsl and triangle_setup.wgsl, and
// before a block saying how clusters are culled by occlusion: occlusion_none.wgsl, or
// cluster_occlusion.wgsl with occlusion_first.wgsl or occlusion_second.wgsl.

// The lists' lengths: the spanning pieces and clusters (the first two, which
// tile_raster.wgsl reads), the entries large triangles took, the items, the fallback
// clusters, and the slots the clusters binned by triangle asked for (past the slots
// there are where some overflowed).
struct BinCounts {
    spanning: atomic<u32>,
    spanning_clusters: atomic<u32>,
    large_entries: atomic<u32>,
    items: atomic<u32>,
    fallback: atomic<u32>,
    slots: atomic<u32>,
}

// A cluster binned by triangle: its index, and the slot of its first triangle (the
// others follow).
struct FallbackCluster {
    cluster: u32,
    first_slot: u32,
}

@group(1) @binding(0) var<storage, read> draws: array<RasterDraw>;
@group(1) @binding(1) var<storage, read_write> tile_ends: array<atomic<u32>>;
@group(1) @binding(2) var<storage, read_write> tile_starts: array<u32>;
@group(1) @binding(3) var<storage, read_write> tile_entries: array<u32>;
@group(1) @binding(4) var<storage, read_write> spanning: array<u32>;
@group(1) @binding(5) var<storage, read_write> bin_counts: BinCounts;
// Per slot, a spanning triangle's `t` and pixel bounds.
@group(1) @binding(6) var<storage, read_write> spanning_triangles: array<Spanning>;
// A large triangle's item: its slot, its tiles (min and max corners, each x | y << 16),
// and the first of its tiles (in rows across its bounds) the item lists.
@group(1) @binding(7) var<storage, read_write> items: array<vec4<u32>>;
// Per slot, a binned triangle set up (written by cs_bins_count), as its tiles read it.
@group(1) @binding(8) var<storage, read_write> records: array<ScreenTriangle>;
@group(1) @binding(9) var<storage, read> clusters: array<RasterCluster>;
// The clusters binned by triangle, with their slots.
@group(1) @binding(10) var<storage, read_write> fallback: array<FallbackCluster>;
// What became of the cluster each invocation of cs_clusters_count took (CLUSTER_CULLED,
// ...), for cs_clusters_fill: an occlusion test listing a cluster is made once.
@group(1) @binding(11) var<storage, read_write> cluster_kinds: array<u32>;
// Per tile, 1 where a micro cluster's pixel bounds touch it (its keys are cleared before
// micro_raster.wgsl's atomics, and merged by the tile raster), else 0.
@group(1) @binding(12) var<storage, read_write> micro_tiles: array<atomic<u32>>;
// The micro clusters, each rasterised a triangle an invocation (micro_raster.wgsl).
struct MicroClusters {
    count: atomic<u32>,
    ids: array<u32>,
}
@group(1) @binding(13) var<storage, read_write> micro: MicroClusters;
// The clusters whose slots overflowed and that no tile's cluster list can take, each with
// pixel bounds that hold its triangles' (the whole output where it crosses a depth
// plane): every tile reads them.
@group(1) @binding(14) var<storage, read_write> spanning_clusters: array<Spanning>;
// The workgroups of the dispatches binning the fallback clusters (x, y, z: one workgroup
// per cluster, in rows of at most 65,535), then those of the micro raster's (the same,
// per micro cluster), bound only for cs_clusters_args, which writes them.
@group(3) @binding(0) var<storage, read_write> fallback_args: array<u32, 6>;

// The raster's tile side in pixels.
override TILE: u32;
// common/gpu/bin_sizes.rs sizes the entries by it.
override BINNED_TILES: u32;
// cs_bins_count_items' and cs_bins_fill_items' grid of workgroups.
override ITEM_GROUPS: u32;
// Whether clusters are culled, and whether those that may be are binned whole
// (visibility_compute.rs's `clusters` parameter): without either, every triangle is
// binned by itself, as before clusters.
override CULL_CLUSTERS: bool = true;
override WHOLE_CLUSTERS: bool = true;
// The most tiles a cluster listed whole touches: each of them sets up all of the
// cluster's triangles. common/gpu/bin_sizes.rs sizes the entries by it.
override CLUSTER_TILES: u32;
// The most pixels per triangle a cluster's pixel bounds (a pixel wider on each side than
// its corners') may hold for the cluster to be micro (visibility_compute.rs's `micro`):
// its triangles are then about a pixel or two, and each invocation of micro_raster.wgsl
// scans at most its cluster's bounds. 0: no cluster is micro.
override MICRO_PIXELS: u32 = 0u;
const BIN_GROUP: u32 = 64u;
const ITEM_TILES: u32 = 64u;
const SCAN_GROUP: u32 = 256u;

var<workgroup> scan: array<u32, SCAN_GROUP>;

fn invocation(id: vec3<u32>, groups: vec3<u32>) -> u32 {
    return id.x + id.y * groups.x * BIN_GROUP;
}

fn tiles_across() -> u32 {
    return (output_size().x + TILE - 1u) / TILE;
}

// The tiles: the cluster lists' counts and starts follow the triangle lists'.
fn tile_total() -> u32 {
    return arrayLength(&tile_starts) / 2u;
}

@compute @workgroup_size(64)
fn cs_bins_clear(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = invocation(id, groups);
    if i == 0u {
        occlusion_clear();
        atomicStore(&bin_counts.spanning, 0u);
        atomicStore(&bin_counts.spanning_clusters, 0u);
        atomicStore(&bin_counts.large_entries, 0u);
        atomicStore(&bin_counts.items, 0u);
        atomicStore(&bin_counts.fallback, 0u);
        atomicStore(&bin_counts.slots, 0u);
        atomicStore(&micro.count, 0u);
    }
    if i < arrayLength(&tile_ends) {
        atomicStore(&tile_ends[i], 0u);
    }
    if i < arrayLength(&micro_tiles) {
        atomicStore(&micro_tiles[i], 0u);
    }
}

// The t-th triangle's tiles (min and max corners, inclusive) when it lies within the
// depth planes and covers some pixel (else max < min), its pixel bounds, and the
// triangle set up.
struct Tiles {
    tiles: vec4<u32>,
    pixels: vec4<i32>,
    clipped: bool,
    screen: ScreenTriangle,
}

fn tiles_of(t: u32) -> Tiles {
    var out: Tiles;
    out.tiles = vec4<u32>(1u, 1u, 0u, 0u);
    out.pixels = vec4<i32>(0, 0, -1, -1);
    out.clipped = true;
    let triangle = clip_triangle(t);
    if !unclipped(triangle) {
        return out;
    }
    out.clipped = false;
    let screen = whole_triangle(triangle);
    let bounds = pixel_bounds(screen);
    if screen.area > 0.0 && all(bounds.xy <= bounds.zw) {
        out.pixels = bounds;
        out.tiles = vec4<u32>(bounds) / TILE;
        out.screen = screen;
    }
    return out;
}

fn tile_count(tiles: vec4<u32>) -> u32 {
    let extent = tiles.zw - tiles.xy + 1u;
    return extent.x * extent.y;
}

// `pixels` (min and max corners, inclusive, not negative) packed for a spanning entry of
// `index`.
fn spanning_entry(index: u32, pixels: vec4<i32>) -> Spanning {
    return Spanning(index, pack(vec2<u32>(pixels.xy)), pack(vec2<u32>(pixels.zw)));
}

// Adds `pieces` pieces of triangle `b`, whose pixel bounds are `pixels`, to the spanning
// list.
fn add_spanning(b: BinnedTriangle, pieces: u32, pixels: vec4<i32>) {
    spanning_triangles[b.slot] = spanning_entry(b.t, pixels);
    let first = atomicAdd(&bin_counts.spanning, pieces);
    for (var k = 0u; k < pieces; k++) {
        if first + k < arrayLength(&spanning) {
            spanning[first + k] = (b.slot << 2u) | k;
        }
    }
}

// A triangle of a fallback cluster: its `t` (NO_TRIANGLE for none) and its slot.
struct BinnedTriangle {
    t: u32,
    slot: u32,
}

const NO_TRIANGLE: u32 = 0xffffffffu;

// The triangle of a fallback cluster that invocation `local` of workgroup `group` bins
// (cs_bins_count, cs_bins_fill: a workgroup per cluster, as cs_clusters_args counts
// them).
fn fallback_triangle(group: vec3<u32>, groups: vec3<u32>, local: u32) -> BinnedTriangle {
    // The last row of workgroups runs past the list.
    let listed = group.x + group.y * groups.x;
    if listed >= atomicLoad(&bin_counts.fallback) {
        return BinnedTriangle(NO_TRIANGLE, 0u);
    }
    let f = fallback[listed];
    let c = clusters[f.cluster];
    if local >= c.triangles {
        return BinnedTriangle(NO_TRIANGLE, 0u);
    }
    return BinnedTriangle(c.first + local, f.first_slot + local);
}

@compute @workgroup_size(64)
fn cs_bins_count(@builtin(workgroup_id) group: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>, @builtin(local_invocation_index) local: u32) {
    let binned = fallback_triangle(group, groups, local);
    let t = binned.t;
    if t == NO_TRIANGLE {
        return;
    }
    let b = tiles_of(t);
    if b.clipped {
        // Its pieces' bounds together.
        let triangle = clip_triangle(t);
        let pieces = clipped_count(triangle);
        var pixels = vec4<i32>(1 << 30, 1 << 30, -1, -1);
        for (var k = 0u; k < pieces; k++) {
            let bounds = pixel_bounds(clipped_triangle(triangle, k));
            pixels = vec4<i32>(min(pixels.xy, bounds.xy), max(pixels.zw, bounds.zw));
        }
        if pieces > 0u && all(pixels.xy <= pixels.zw) {
            add_spanning(binned, pieces, pixels);
        }
        return;
    }
    if any(b.tiles.zw < b.tiles.xy) {
        return;
    }
    // Its tiles read it set up, unless it spans (then they set it up themselves).
    records[binned.slot] = b.screen;
    let count = tile_count(b.tiles);
    if count <= BINNED_TILES {
        for (var y = b.tiles.y; y <= b.tiles.w; y++) {
            for (var x = b.tiles.x; x <= b.tiles.z; x++) {
                atomicAdd(&tile_ends[y * tiles_across() + x], 1u);
            }
        }
        return;
    }
    // Room after BINNED_TILES entries per slot and CLUSTER_TILES per cluster. Once it is
    // known full, nothing more is taken (so the count cannot run on towards 2^32);
    // tile_raster.wgsl checks each tile's list against the entries all the same.
    let room = arrayLength(&tile_entries) - BINNED_TILES * arrayLength(&records) - CLUSTER_TILES * arrayLength(&clusters);
    if atomicLoad(&bin_counts.large_entries) > room {
        add_spanning(binned, 1u, b.pixels);
        return;
    }
    let taken = atomicAdd(&bin_counts.large_entries, count);
    if count > room || taken > room - count {
        add_spanning(binned, 1u, b.pixels);
        return;
    }
    let item_count = (count + ITEM_TILES - 1u) / ITEM_TILES;
    let first = atomicAdd(&bin_counts.items, item_count);
    for (var i = 0u; i < item_count; i++) {
        if first + i < arrayLength(&items) {
            items[first + i] = vec4<u32>(binned.slot, pack(b.tiles.xy), pack(b.tiles.zw), i * ITEM_TILES);
        }
    }
}

// The tile an invocation `local` of an item's workgroup lists, or none (NO_TILE).
const NO_TILE: u32 = 0xffffffffu;

fn item_tile(item: vec4<u32>, local: u32) -> u32 {
    let low = unpack(item.y);
    let extent = unpack(item.z) - low + 1u;
    let k = item.w + local;
    if local >= ITEM_TILES || k >= extent.x * extent.y {
        return NO_TILE;
    }
    let tile = low + vec2<u32>(k % extent.x, k / extent.x);
    return tile.y * tiles_across() + tile.x;
}

fn item_total() -> u32 {
    return min(atomicLoad(&bin_counts.items), arrayLength(&items));
}

@compute @workgroup_size(64)
fn cs_bins_count_items(@builtin(workgroup_id) group: vec3<u32>, @builtin(local_invocation_index) local: u32) {
    for (var i = group.x; i < item_total(); i += ITEM_GROUPS) {
        let tile = item_tile(items[i], local);
        if tile != NO_TILE {
            atomicAdd(&tile_ends[tile], 1u);
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

// Adds `listed` (a slot or a cluster) to list `tile`.
fn add_entry(tile: u32, listed: u32) {
    let entry = atomicAdd(&tile_ends[tile], 1u);
    if entry < arrayLength(&tile_entries) {
        tile_entries[entry] = listed;
    }
}

@compute @workgroup_size(64)
fn cs_bins_fill(@builtin(workgroup_id) group: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>, @builtin(local_invocation_index) local: u32) {
    let binned = fallback_triangle(group, groups, local);
    if binned.t == NO_TRIANGLE {
        return;
    }
    let b = tiles_of(binned.t);
    if b.clipped || any(b.tiles.zw < b.tiles.xy) || tile_count(b.tiles) > BINNED_TILES {
        return;
    }
    for (var y = b.tiles.y; y <= b.tiles.w; y++) {
        for (var x = b.tiles.x; x <= b.tiles.z; x++) {
            add_entry(y * tiles_across() + x, binned.slot);
        }
    }
}

@compute @workgroup_size(64)
fn cs_bins_fill_items(@builtin(workgroup_id) group: vec3<u32>, @builtin(local_invocation_index) local: u32) {
    for (var i = group.x; i < item_total(); i += ITEM_GROUPS) {
        let item = items[i];
        let tile = item_tile(item, local);
        if tile != NO_TILE {
            add_entry(tile, item.x);
        }
    }
}

// What becomes of a cluster this frame (cluster_bins, then binned_by_triangle).
const CLUSTER_CULLED: u32 = 0u;
const CLUSTER_WHOLE: u32 = 1u;
const CLUSTER_BY_TRIANGLE: u32 = 2u;
const CLUSTER_MICRO: u32 = 3u;
const CLUSTER_SPANNING: u32 = 4u;

// Whether `model`, a camera-relative object-to-world matrix, keeps angles and
// orientation (a rotation, a uniform scale, a translation), under which a normal cone
// made in object space bounds the world's normals as it bounds the object's.
fn keeps_angles(model: mat4x4<f32>) -> bool {
    let x = model[0].xyz;
    let y = model[1].xyz;
    let z = model[2].xyz;
    let s = dot(x, x);
    let tolerance = 1e-4 * s;
    return abs(dot(y, y) - s) <= tolerance && abs(dot(z, z) - s) <= tolerance
        && abs(dot(x, y)) <= tolerance && abs(dot(y, z)) <= tolerance && abs(dot(z, x)) <= tolerance
        && dot(cross(x, y), z) > 0.0;
}

// Whether every triangle of cluster `c` of a draw that culls back faces shows its back to
// the camera, at the origin of camera-relative space (meshoptimizer's cone test, with a
// margin for rounding).
fn back_facing(c: RasterCluster, model: mat4x4<f32>) -> bool {
    if c.cone_cutoff >= 1.0 || !keeps_angles(model) {
        return false;
    }
    let scale = length(model[0].xyz);
    let center = (model * vec4<f32>(c.center, 1.0)).xyz;
    let axis = (model * vec4<f32>(c.cone_axis, 0.0)).xyz / scale;
    let distance = length(center);
    return dot(center, axis) >= c.cone_cutoff * distance + c.radius * scale * 1.001 + 1e-5 * distance;
}

// A cluster's box seen from this frame's camera: whether it lies wholly outside one
// plane of the view volume (with a margin for rounding), whether it crosses a depth
// plane or the camera's (some corner outside, or within the margin), and the pixels its
// corners' bounds touch, a pixel wider on each side for rounding, clamped to the output
// (the whole output where it crosses).
struct ClusterScreen {
    outside: bool,
    crosses: bool,
    pixels: vec4<u32>,
}

fn cluster_screen(c: RasterCluster) -> ClusterScreen {
    let model = meshes[draws[c.draw].mesh].model;
    // Per plane (x >= -w, x <= w, y >= -w, y <= w, z >= 0, z <= w), whether every
    // corner is outside it, and whether some corner is outside a depth plane.
    var outside = vec3<bool>(true);
    var outside_low = vec3<bool>(true);
    var crosses = false;
    var low = vec2<f32>(1e30);
    var high = vec2<f32>(-1e30);
    for (var k = 0u; k < 8u; k++) {
        let corner = select(c.min, c.max, vec3<bool>((k & 1u) != 0u, (k & 2u) != 0u, (k & 4u) != 0u));
        let clip = camera.view_proj * (model * vec4<f32>(corner, 1.0));
        let margin = 1e-5 * (abs(clip.w) + abs(clip.x) + abs(clip.y) + abs(clip.z));
        let w = vec3<f32>(clip.w, clip.w, clip.w);
        outside = outside & (clip.xyz - w > vec3<f32>(margin));
        outside_low = outside_low & (vec3<f32>(clip.xy, clip.z) < vec3<f32>(-clip.w, -clip.w, 0.0) - vec3<f32>(margin));
        let planes = depth_planes(clip);
        crosses = crosses || clip.w <= 0.0 || any(planes < vec2<f32>(margin));
        if clip.w > 0.0 {
            let screen = to_screen(clip).xy;
            low = min(low, screen);
            high = max(high, screen);
        }
    }
    let size = vec2<f32>(output_size());
    var pixels = vec4<u32>(vec2<u32>(0u), output_size() - 1u);
    if !crosses {
        let first = clamp(floor(low) - 1.0, vec2<f32>(0.0), size - 1.0);
        let last = clamp(floor(high) + 1.0, vec2<f32>(0.0), size - 1.0);
        pixels = vec4<u32>(vec2<u32>(first), vec2<u32>(last));
    }
    return ClusterScreen(any(outside) || any(outside_low), crosses, pixels);
}

// Cluster `c` seen as `screen` this frame: culled (CULL_CLUSTERS) where its box lies
// wholly outside one plane of the view volume or its normal cone shows only back faces;
// where its box lies within the depth planes, in front of the camera, micro
// (MICRO_PIXELS) where its pixel bounds hold at most MICRO_PIXELS pixels per triangle,
// or binned whole (WHOLE_CLUSTERS) where they touch at most CLUSTER_TILES tiles; else
// binned by triangle.
fn cluster_bins(c: RasterCluster, screen: ClusterScreen) -> u32 {
    if !CULL_CLUSTERS && !WHOLE_CLUSTERS {
        return CLUSTER_BY_TRIANGLE;
    }
    if CULL_CLUSTERS {
        let draw = draws[c.draw];
        let cull_back = (draw.flags & CULL_BACK) != 0u;
        if screen.outside || (cull_back && back_facing(c, meshes[draw.mesh].model)) {
            return CLUSTER_CULLED;
        }
    }
    if (!WHOLE_CLUSTERS && MICRO_PIXELS == 0u) || screen.crosses {
        return CLUSTER_BY_TRIANGLE;
    }
    let extent = vec2<f32>(screen.pixels.zw - screen.pixels.xy + 1u);
    if extent.x * extent.y <= f32(MICRO_PIXELS * c.triangles) {
        return CLUSTER_MICRO;
    }
    if WHOLE_CLUSTERS && whole_fits(screen) {
        return CLUSTER_WHOLE;
    }
    return CLUSTER_BY_TRIANGLE;
}

// Whether a cluster seen as `screen` may be listed whole: it lies within the depth
// planes, and touches at most CLUSTER_TILES tiles.
fn whole_fits(screen: ClusterScreen) -> bool {
    return !screen.crosses && tile_count(screen.pixels / TILE) <= CLUSTER_TILES;
}

// Cluster `index`, seen as `screen`, binned by triangle: given its triangles' slots and
// listed in `fallback`, or, where the slots run out, listed whole where it may be, else
// spanning.
fn binned_by_triangle(index: u32, screen: ClusterScreen) -> u32 {
    let triangles = clusters[index].triangles;
    let first = atomicAdd(&bin_counts.slots, triangles);
    if first + triangles <= arrayLength(&records) {
        fallback[atomicAdd(&bin_counts.fallback, 1u)] = FallbackCluster(index, first);
        return CLUSTER_BY_TRIANGLE;
    }
    if whole_fits(screen) {
        return CLUSTER_WHOLE;
    }
    let listed = atomicAdd(&bin_counts.spanning_clusters, 1u);
    if listed < arrayLength(&spanning_clusters) {
        spanning_clusters[listed] = spanning_entry(index, vec4<i32>(screen.pixels));
    }
    return CLUSTER_SPANNING;
}

// The cluster invocation `i` of cs_clusters_count and cs_clusters_fill takes, or
// NO_CLUSTER: without occlusion culling and in its first phase, the i-th.
const NO_CLUSTER: u32 = 0xffffffffu;

fn every_cluster(i: u32) -> u32 {
    return select(NO_CLUSTER, i, i < arrayLength(&clusters));
}

@compute @workgroup_size(64)
fn cs_clusters_count(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = invocation(id, groups);
    let c = listed_cluster(i);
    if c == NO_CLUSTER {
        return;
    }
    let screen = cluster_screen(clusters[c]);
    var kind = occlusion_kind(c, cluster_bins(clusters[c], screen));
    if kind == CLUSTER_BY_TRIANGLE {
        kind = binned_by_triangle(c, screen);
    }
    cluster_kinds[i] = kind;
    let tiles = screen.pixels / TILE;
    if kind == CLUSTER_WHOLE {
        for (var y = tiles.y; y <= tiles.w; y++) {
            for (var x = tiles.x; x <= tiles.z; x++) {
                atomicAdd(&tile_ends[tile_total() + y * tiles_across() + x], 1u);
            }
        }
    } else if kind == CLUSTER_MICRO {
        micro.ids[atomicAdd(&micro.count, 1u)] = c;
        for (var y = tiles.y; y <= tiles.w; y++) {
            for (var x = tiles.x; x <= tiles.z; x++) {
                atomicStore(&micro_tiles[y * tiles_across() + x], 1u);
            }
        }
    }
}

// The indirect arguments of a dispatch of one workgroup per entry of a list `count` long,
// from `at` in `fallback_args`: rows of at most 65,535 workgroups.
fn list_args(count: u32, at: u32) {
    let x = min(count, 65535u);
    fallback_args[at] = x;
    fallback_args[at + 1u] = select(0u, (count + x - 1u) / max(x, 1u), x > 0u);
    fallback_args[at + 2u] = 1u;
}

@compute @workgroup_size(1)
fn cs_clusters_args() {
    list_args(atomicLoad(&bin_counts.fallback), 0u);
    list_args(atomicLoad(&micro.count), 3u);
}

@compute @workgroup_size(64)
fn cs_clusters_fill(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = invocation(id, groups);
    let c = listed_cluster(i);
    if c == NO_CLUSTER || cluster_kinds[i] != CLUSTER_WHOLE {
        return;
    }
    // The tiles cs_clusters_count counted, found again the same way.
    let tiles = cluster_screen(clusters[c]).pixels / TILE;
    for (var y = tiles.y; y <= tiles.w; y++) {
        for (var x = tiles.x; x <= tiles.z; x++) {
            add_entry(tile_total() + y * tiles_across() + x, c);
        }
    }
}
