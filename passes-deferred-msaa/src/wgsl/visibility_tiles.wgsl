// A visibility buffer that never leaves the chip: the tiled shading pass's workgroup
// covers its tile (tile_raster.wgsl) and keeps the keys in workgroup memory
// (`tile_keys`), where `sample_id` and `sample_depth` read them as
// visibility_samples.wgsl reads a compute rasteriser's buffer. Composed after
// tile_raster.wgsl, inside light_tiled.wgsl's generated block, before
// visibility_read.wgsl.

// Each pixel's samples' keys (triangle_setup.wgsl's), at the pixel's index in the tile
// times SAMPLES plus the sample.
var<workgroup> tile_keys: array<vec2<u32>, TILE * TILE * SAMPLES>;

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

// Covers the tile at `origin` and leaves its keys in tile_keys for after the next barrier.
fn raster_tile(origin: vec2<u32>, local: u32) {
    let keys = cover_tile(origin, local);
    for (var s = 0u; s < SAMPLES; s++) {
        tile_keys[local * SAMPLES + s] = key_of_sample(keys, s);
    }
}
