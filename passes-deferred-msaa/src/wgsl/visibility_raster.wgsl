// The visibility buffer rasterised in compute (passes/visibility_compute.rs): every
// sample keeps the nearest triangle as one 64-bit key (triangle_setup.wgsl's), so
// a single atomicMax is the depth test and the ID write together (no render targets, no
// ROPs: the cost of a multisampled raster pass on chips with few of them).
//
// Three dispatches, in order:
// 1. cs_clear: every key to 0, the work lists emptied.
// 2. cs_raster: one invocation per triangle of the opaque draws. It sets the triangle up
//    (triangle_setup.wgsl), then covers a small one's samples itself; a larger one is
//    split into blocks of 8 x 8 pixels, listed as items of up to ITEM_BLOCKS blocks, so
//    that the work of a floor covering the screen spreads over the whole GPU.
// 3. cs_raster_items: a fixed grid of 8 x 8 workgroups takes the items in turn, an
//    invocation per pixel of a block.
//
// Composed after common.wgsl, scene.wgsl, geometry.wgsl and triangle_setup.wgsl.

// The work lists' lengths.
struct Counts {
    listed: atomic<u32>,
    items: atomic<u32>,
}

@group(1) @binding(0) var<storage, read_write> keys: array<atomic<u64>>;
@group(1) @binding(1) var<storage, read> draws: array<RasterDraw>;
@group(1) @binding(2) var<storage, read_write> counts: Counts;
// Triangles too large for one invocation.
@group(1) @binding(3) var<storage, read_write> listed: array<ScreenTriangle>;
// Items: a listed triangle and its first block (NO_ITEM: none).
@group(1) @binding(4) var<storage, read_write> items: array<vec2<u32>>;

// A triangle whose bounding box holds more pixels than this is listed.
const SMALL_PIXELS: u32 = 32u;
const BLOCK: u32 = 8u;
const ITEM_BLOCKS: u32 = 16u;
const NO_ITEM: u32 = 0xffffffffu;
// cs_raster's workgroup, and cs_raster_items' grid of workgroups.
const RASTER_GROUP: u32 = 64u;
override ITEM_GROUPS: u32 = 1024u;

@compute @workgroup_size(64)
fn cs_clear(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = id.x + id.y * groups.x * 64u;
    if i == 0u {
        atomicStore(&counts.listed, 0u);
        atomicStore(&counts.items, 0u);
    }
    if i < arrayLength(&keys) {
        // A min with 0 clears with the 64-bit operations every device with 64-bit
        // atomics has (loads and stores of them are a further feature).
        atomicMin(&keys[i], 0lu);
    }
}

// Tests every sample of `pixel` against the triangle and keeps the nearer key.
fn cover_pixel(pixel: vec2<u32>, t: ScreenTriangle) {
    if !mask_passes(pixel, t) {
        return;
    }
    let owns = owned_edges(t);
    let base = (pixel.y * output_size().x + pixel.x) * SAMPLES;
    for (var s = 0u; s < SAMPLES; s++) {
        let key = sample_key(pixel, s, t, owns);
        if key.x != 0u {
            atomicMax(&keys[base + s], (u64(key.y) << 32u) | u64(key.x));
        }
    }
}

// A screen triangle: covered here when small, else listed with its items.
fn raster_screen(t: ScreenTriangle) {
    if t.area == 0.0 {
        return;
    }
    let bounds = pixel_bounds(t);
    if any(bounds.zw < bounds.xy) {
        return;
    }
    let extent = vec2<u32>(bounds.zw - bounds.xy) + 1u;
    if extent.x * extent.y > SMALL_PIXELS {
        let blocks = (extent + BLOCK - 1u) / BLOCK;
        let count = blocks.x * blocks.y;
        let item_count = (count + ITEM_BLOCKS - 1u) / ITEM_BLOCKS;
        let slot = atomicAdd(&counts.listed, 1u);
        let first_item = atomicAdd(&counts.items, item_count);
        let fits = slot < arrayLength(&listed) && first_item + item_count <= arrayLength(&items);
        if fits {
            listed[slot] = t;
        }
        // A list is full: the items this triangle took that fit are marked empty (other
        // triangles may have taken items after them, so the count stays), and it is
        // covered here, slowly but exactly.
        let end = min(first_item + item_count, arrayLength(&items));
        for (var i = first_item; i < end; i++) {
            items[i] = select(vec2<u32>(NO_ITEM, 0u), vec2<u32>(slot, (i - first_item) * ITEM_BLOCKS), fits);
        }
        if fits {
            return;
        }
    }
    for (var y = bounds.y; y <= bounds.w; y++) {
        for (var x = bounds.x; x <= bounds.z; x++) {
            cover_pixel(vec2<u32>(vec2<i32>(x, y)), t);
        }
    }
}

@compute @workgroup_size(64)
fn cs_raster(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let t = gid.x + gid.y * groups.x * RASTER_GROUP;
    if t >= triangle_count() {
        return;
    }
    let triangle = clip_triangle(t);
    if unclipped(triangle) {
        raster_screen(whole_triangle(triangle));
    } else {
        let count = clipped_count(triangle);
        for (var k = 0u; k < count; k++) {
            raster_screen(clipped_triangle(triangle, k));
        }
    }
}

@compute @workgroup_size(8, 8)
fn cs_raster_items(@builtin(workgroup_id) group: vec3<u32>, @builtin(local_invocation_id) local: vec3<u32>) {
    let item_count = min(atomicLoad(&counts.items), arrayLength(&items));
    for (var i = group.x; i < item_count; i += ITEM_GROUPS) {
        let item = items[i];
        if item.x == NO_ITEM {
            continue;
        }
        let t = listed[item.x];
        let bounds = pixel_bounds(t);
        let extent = vec2<u32>(bounds.zw - bounds.xy) + 1u;
        let blocks = (extent + BLOCK - 1u) / BLOCK;
        let last = min(item.y + ITEM_BLOCKS, blocks.x * blocks.y);
        for (var k = item.y; k < last; k++) {
            let at = vec2<u32>(k % blocks.x, k / blocks.x) * BLOCK + local.xy;
            if all(at < extent) {
                cover_pixel(vec2<u32>(bounds.xy) + at, t);
            }
        }
    }
}
