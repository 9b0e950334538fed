// Occlusion culling of the draws' clusters against a depth pyramid, in two phases
// (visibility_compute.rs's `pyramid` and `occluded` slots; Haar and Aaltonen, "GPU-Driven
// Rendering Pipelines", SIGGRAPH 2015; docs/design/compute-raster.md). The first phase
// bins the clusters the previous frame's pyramid does not hide, seen through the previous
// frame's camera, and lists the others in `occluded` (occlusion_first.wgsl); the second
// tests those against the pyramid of what the first drew, through this frame's camera,
// and bins the ones it does not hide (occlusion_second.wgsl). Only the second test decides
// what is never drawn, and it is conservative: a cluster is hidden where every sample it
// may cover lies strictly behind what the first phase drew there, so none of its keys
// could win, and the image is the one without occlusion culling, exactly
// (tests/culling.rs). The first test may be wrong (things move, the camera turns): that
// costs the second phase work, never a pixel.
//
// Composed after bin_triangles.wgsl, which calls each phase's occlusion_clear,
// listed_cluster and occlusion_kind; group 3 binds the pyramid (binding 1) and the list
// (binding 2) to the dispatches that cull clusters.

@group(3) @binding(1) var pyramid: texture_2d<f32>;

// The clusters the first phase did not draw, and counts the tests can read: how many it
// listed (`count`, which may pass the room: those past it were drawn), and how many of
// those the second phase drew (`revealed`).
struct OccludedClusters {
    count: atomic<u32>,
    revealed: atomic<u32>,
    _pad0: u32,
    _pad1: u32,
    ids: array<u32>,
}

@group(3) @binding(2) var<storage, read_write> occluded: OccludedClusters;

// A cluster's nearest depth is raised by this share of itself before the test: the raster
// interpolates a sample's depth from its triangle's corners' (tile_raster.wgsl's
// cover_lanes), exact to their range but for rounding, a few ulps of the largest.
const DEPTH_MARGIN: f32 = 1e-3;

// Whether the depths `pyramid` holds hide cluster `c`, whose mesh's camera-relative
// transform is `model`, seen through `clip_from_relative`: its box lies wholly in front
// of the camera and behind the near plane, and its nearest depth (raised by DEPTH_MARGIN)
// is behind the farthest depth the pyramid holds over every pixel its corners' bounds
// touch (a pixel wider on each side for rounding), read at the finest level where those
// are at most 2 x 2 texels (depth_pyramid.wgsl's mapping). A box reaching the camera's
// plane is never hidden (its pixels are unbounded), nor where the pyramid is zeros (the
// first frame, or nothing drawn there: the far depth).
fn pyramid_hides(c: RasterCluster, model: mat4x4<f32>, clip_from_relative: mat4x4<f32>) -> bool {
    var low = vec2<f32>(1e30);
    var high = vec2<f32>(-1e30);
    var nearest = 0.0;
    for (var k = 0u; k < 8u; k++) {
        let corner = select(c.min, c.max, vec3<bool>((k & 1u) != 0u, (k & 2u) != 0u, (k & 4u) != 0u));
        let clip = clip_from_relative * (model * vec4<f32>(corner, 1.0));
        if clip.w <= 0.0 || clip.z >= clip.w {
            return false;
        }
        let screen = to_screen(clip);
        low = min(low, screen.xy);
        high = max(high, screen.xy);
        nearest = max(nearest, screen.z);
    }
    let output = camera.viewport;
    let first = vec2<u32>(clamp(floor(low) - 1.0, vec2<f32>(0.0), output - 1.0));
    let last = vec2<u32>(clamp(floor(high) + 1.0, vec2<f32>(0.0), output - 1.0));
    let size = textureDimensions(pyramid);
    let texels_low = first * size / vec2<u32>(output);
    let texels_high = last * size / vec2<u32>(output);
    let levels = textureNumLevels(pyramid);
    var level = 0u;
    while level + 1u < levels && any((texels_high >> vec2<u32>(level)) > (texels_low >> vec2<u32>(level)) + 1u) {
        level++;
    }
    // A level's size by WebGPU's rule.
    let level_last = max(size >> vec2<u32>(level), vec2<u32>(1u)) - 1u;
    let a = min(texels_low >> vec2<u32>(level), level_last);
    let b = min(texels_high >> vec2<u32>(level), level_last);
    if any(b > a + 1u) {
        // A pyramid of too few levels for these bounds.
        return false;
    }
    // Each invocation reads at its own level, in the turn of a loop over the levels where
    // every invocation's `at` is that level: given levels that differ, llvmpipe answered
    // textureDimensions(pyramid, level) with one invocation's for all of them (measured),
    // and a load may do the same, which would read other texels.
    var farthest = 0.0;
    for (var at = 0u; at < levels; at++) {
        if at == level {
            farthest = min(
                min(textureLoad(pyramid, a, at).x, textureLoad(pyramid, vec2<u32>(b.x, a.y), at).x),
                min(textureLoad(pyramid, vec2<u32>(a.x, b.y), at).x, textureLoad(pyramid, b, at).x),
            );
        }
    }
    return nearest * (1.0 + DEPTH_MARGIN) < farthest;
}

// The camera-relative transform of cluster `c`'s mesh.
fn cluster_model(c: RasterCluster) -> mat4x4<f32> {
    return meshes[draws[c.draw].mesh].model;
}
