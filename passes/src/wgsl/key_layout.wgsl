// Where a compute rasteriser's visibility buffer (common/visibility_samples.rs) keeps each
// sample's key, for the pass writing it (raster_tiles.wgsl) and those reading it
// (visibility_samples.wgsl): a plane per sample, each row by row, of 64-bit keys as two
// words, the triangle's ID + 1 low and the reversed-Z depth's bits high (0 0: nothing
// drawn, at the far depth 0). A depth is never negative, so the sign bit of sample 0's
// depth is free: it is set (SEVERAL_SURFACES) where the pixel's samples show more than one
// triangle. Most pixels show one, and their readers load sample 0's plane only, a quarter
// of a 4x buffer; the other planes are read at the edges (and with visibility_compute's
// `other_samples: at_edges` written only there). Composed after scene.wgsl.

const SEVERAL_SURFACES: u32 = 0x80000000u;

fn key_index(pixel: vec2<u32>, s: u32) -> u32 {
    let size = vec2<u32>(camera.viewport);
    return (s * size.y + pixel.y) * size.x + pixel.x;
}
