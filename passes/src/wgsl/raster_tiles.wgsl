// The visibility buffer rasterised tile by tile (passes/visibility_compute.rs): a workgroup
// per tile covers its triangles in registers (tile_raster.wgsl) and stores each pixel's
// keys once, with plain stores, into the buffer a compute rasteriser's keys go to
// (visibility_samples.wgsl reads it): no atomics into memory, and no 64-bit integers.
// Sample 0's key says whether the pixel's samples show more than one triangle
// (SEVERAL_SURFACES), which only this pass knows without reading them all. An invocation
// stores the keys of the pixel it covered (tile_raster.wgsl's pixel_in_tile). The second
// phase of occlusion culling (MERGE) adds its triangles to the keys the first phase
// stored, at the pixels it covers; with micro clusters (MICRO), a tile they touch adds its
// triangles to the keys micro_raster.wgsl left there, and flags its pixels. Composed
// after tile_raster.wgsl and key_layout.wgsl.

@group(1) @binding(0) var<storage, read_write> written_keys: array<vec2<u32>>;
// bin_triangles.wgsl's micro_tiles: 1 where micro_raster.wgsl wrote keys in the tile.
@group(1) @binding(10) var<storage, read> micro_tiles: array<u32>;

// Whether the keys of samples other than 0 are stored at every pixel, or only where the
// pixel's samples show more than one triangle (visibility_compute.rs's other_samples).
override OTHERS_EVERYWHERE: bool = true;
// Whether the buffer holds keys already, every sample's (the first phase of occlusion
// culling stores them all), which this pass's triangles are added to: each sample keeps
// the larger key, as if the two passes' triangles had been covered together. A pixel
// this pass covers no sample of keeps its keys untouched.
override MERGE: bool = false;
// Whether micro clusters were rasterised before this pass (micro_raster.wgsl): in the
// tiles they touch the buffer holds their keys, without flags, every sample's, and
// elsewhere what an earlier frame left.
override MICRO: bool = false;

// Pixel `pixel`'s keys: those `keys` holds, or those stored before where larger, then
// stored with the flag the two together earn (sample 0's, and the others' where
// OTHERS_EVERYWHERE or the pixel shows several triangles). Stored keys that carry their
// flag already (`flagged`: MERGE's) are left as they are where `keys` covers nothing; a
// micro tile's carry none, and are always stored.
fn store_merged(keys: TileKeys, pixel: vec2<u32>, flagged: bool) {
    var merged: array<vec2<u32>, SAMPLES>;
    var covered = false;
    for (var s = 0u; s < SAMPLES; s++) {
        merged[s] = key_of_sample(keys, s);
        covered = covered || merged[s].x != 0u;
    }
    if flagged && !covered {
        return;
    }
    var several = false;
    for (var s = 0u; s < SAMPLES; s++) {
        let stored = written_keys[key_index(pixel, s)];
        let kept = vec2<u32>(stored.x, stored.y & ~SEVERAL_SURFACES);
        if kept.y > merged[s].y || (kept.y == merged[s].y && kept.x > merged[s].x) {
            merged[s] = kept;
        }
        several = several || merged[s].x != merged[0].x;
    }
    let stored = select(1u, SAMPLES, several || OTHERS_EVERYWHERE);
    for (var s = 0u; s < stored; s++) {
        var key = merged[s];
        if s == 0u && several {
            key.y |= SEVERAL_SURFACES;
        }
        written_keys[key_index(pixel, s)] = key;
    }
}

@compute @workgroup_size(TILE, TILE, 1)
fn cs_raster_tiles(
    @builtin(workgroup_id) tile: vec3<u32>,
    @builtin(local_invocation_index) local: u32,
) {
    let origin = tile.xy * TILE;
    let keys = cover_tile(origin, local);
    let pixel = origin + pixel_in_tile(local);
    if all(pixel < output_size()) {
        if MERGE {
            store_merged(keys, pixel, true);
            return;
        }
        let tiles_across = (output_size().x + TILE - 1u) / TILE;
        if MICRO && micro_tiles[tile.y * tiles_across + tile.x] != 0u {
            store_merged(keys, pixel, false);
            return;
        }
        let id0 = LaneU(lane(keys.ids[0], 0u));
        var several = false;
        for (var g = 0u; g < LANE_GROUPS; g++) {
            several = several || any(keys.ids[g] != id0);
        }
        let stored = select(1u, SAMPLES, several || OTHERS_EVERYWHERE);
        for (var s = 0u; s < stored; s++) {
            var key = key_of_sample(keys, s);
            if s == 0u && several {
                key.y |= SEVERAL_SURFACES;
            }
            written_keys[key_index(pixel, s)] = key;
        }
    }
}
