// Micro clusters rasterised a triangle an invocation (Nanite's software raster: Karis,
// "Nanite: A Deep Dive", SIGGRAPH 2021), before the tile raster (raster_tiles.wgsl) covers
// the other clusters' triangles. bin_triangles.wgsl lists a cluster as micro where its
// pixel bounds hold at most MICRO_PIXELS pixels per triangle, and marks the tiles those
// bounds touch. Two dispatches, between the bins' and the tile raster's:
// 1. cs_micro_clear: a workgroup per tile; in a marked tile every sample's key to 0, so
//    that the atomics below start from "nothing drawn".
// 2. cs_micro_raster: a workgroup per micro cluster, an invocation per triangle, which
//    sets its triangle up as the tile raster does (tile_raster.wgsl's cover_triangle), scans
//    the pixels of its bounds, tests their samples exactly as a tile's invocation tests
//    them (edges_at_pixel, mask_passes, cover_lanes: the same coverage, the same depths)
//    and keeps each covered sample's key by a 64-bit atomicMax: depth bits high, ID + 1
//    low (key_layout.wgsl), so that the larger key wins as in the tile raster. No flag:
//    the tile raster then merges its own keys into a marked tile's and sets sample 0's
//    flag where the pixel shows several triangles.
// A triangle's scan is at most its cluster's bounds, MICRO_PIXELS pixels per triangle
// (under lavapipe's 65,535 loop iterations an invocation: docs/design/compute-raster.md).
//
// Needs wgpu's SHADER_INT64 and SHADER_INT64_ATOMIC_MIN_MAX (visibility_compute.rs
// composes it only for devices with both). Binds the tile raster's group 1, but binding 0,
// the keys, as 64-bit atomics. Composed after tile_raster.wgsl and key_layout.wgsl.

@group(1) @binding(0) var<storage, read_write> micro_keys: array<atomic<u64>>;
@group(1) @binding(10) var<storage, read> micro_tiles: array<u32>;
// bin_triangles.wgsl's MicroClusters, read after it is done.
struct MicroList {
    count: u32,
    ids: array<u32>,
}
@group(1) @binding(11) var<storage, read> micro_clusters: MicroList;

@compute @workgroup_size(TILE, TILE, 1)
fn cs_micro_clear(@builtin(workgroup_id) tile: vec3<u32>, @builtin(local_invocation_index) local: u32) {
    let tiles_across = (output_size().x + TILE - 1u) / TILE;
    let pixel = tile.xy * TILE + pixel_in_tile(local);
    if micro_tiles[tile.y * tiles_across + tile.x] == 0u || any(pixel >= output_size()) {
        return;
    }
    for (var s = 0u; s < SAMPLES; s++) {
        atomicStore(&micro_keys[key_index(pixel, s)], 0lu);
    }
}

// Keeps `t`'s key in every sample of its pixel bounds it covers.
fn cover_micro(t: ScreenTriangle) {
    if !(t.area > 0.0) {
        return;
    }
    let cover = cover_triangle(t);
    let bounds = pixel_bounds(t);
    for (var y = bounds.y; y <= bounds.w; y++) {
        for (var x = bounds.x; x <= bounds.z; x++) {
            let pixel = vec2<u32>(u32(x), u32(y));
            let corner = edges_at_pixel(cover, pixel);
            if !mask_passes(cover, corner, pixel) {
                continue;
            }
            var depths: array<LaneU, LANE_GROUPS>;
            var ids: array<LaneU, LANE_GROUPS>;
            cover_lanes(corner, cover, &depths, &ids);
            let keys = TileKeys(depths, ids);
            for (var s = 0u; s < SAMPLES; s++) {
                let key = key_of_sample(keys, s);
                if key.x != 0u {
                    atomicMax(&micro_keys[key_index(pixel, s)], (u64(key.y) << 32u) | u64(key.x));
                }
            }
        }
    }
}

@compute @workgroup_size(64)
fn cs_micro_raster(@builtin(workgroup_id) group: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>, @builtin(local_invocation_index) local: u32) {
    // The last row of workgroups runs past the list.
    let slot = group.x + group.y * groups.x;
    if slot >= micro_clusters.count {
        return;
    }
    let c = clusters[micro_clusters.ids[slot]];
    if local >= c.triangles {
        return;
    }
    // A micro cluster's box lies within the depth planes, so its triangles are whole; a
    // clipped one (rounding) is covered piece by piece, as the tile raster covers it.
    let triangle = clip_triangle(c.first + local);
    if unclipped(triangle) {
        cover_micro(whole_triangle(triangle));
        return;
    }
    for (var k = 0u; k < clipped_count(triangle); k++) {
        cover_micro(clipped_triangle(triangle, k));
    }
}
