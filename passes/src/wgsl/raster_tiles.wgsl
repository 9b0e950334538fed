// The visibility buffer rasterised tile by tile (passes/visibility_compute.rs): a workgroup
// per tile covers its triangles in registers (tile_raster.wgsl) and stores each pixel's
// keys once, with plain stores, into the buffer a compute rasteriser's keys go to
// (visibility_samples.wgsl reads it): no atomics into memory, and no 64-bit integers.
// Sample 0's key says whether the pixel's samples show more than one triangle
// (SEVERAL_SURFACES), which only this pass knows without reading them all. An invocation
// stores the keys of the pixel it covered (tile_raster.wgsl's pixel_in_tile). Composed after
// tile_raster.wgsl and key_layout.wgsl.

@group(1) @binding(0) var<storage, read_write> written_keys: array<vec2<u32>>;

// Whether the keys of samples other than 0 are stored at every pixel, or only where the
// pixel's samples show more than one triangle (visibility_compute.rs's other_samples).
override OTHERS_EVERYWHERE: bool = true;

@compute @workgroup_size(TILE, TILE, 1)
fn cs_raster_tiles(
    @builtin(workgroup_id) tile: vec3<u32>,
    @builtin(local_invocation_index) local: u32,
) {
    let origin = tile.xy * TILE;
    let keys = cover_tile(origin, local);
    let pixel = origin + pixel_in_tile(local);
    if all(pixel < output_size()) {
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
