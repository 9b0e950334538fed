// The shadow maps' compute raster (passes/shadow_raster.rs): the small clusters of each
// view (gpu_scene/view_culling.rs: wholly between the view's depth planes, each spanning
// a few texels) covered one invocation a triangle, the nearest depth of each atlas texel
// kept by atomicMax of its bits inverted (0: nothing), which the `shadow_maps` pass
// writes into the atlas before the hardware draws the large clusters. Composed after
// common.wgsl, scene.wgsl, geometry.wgsl and shadow_views.wgsl.

// A workgroup's triangles: `count` triangles of mesh `mesh` from index `first_index`,
// into view `view` (gpu_scene/shadow_work.rs's items).
struct Item {
    view: u32,
    mesh: u32,
    first_index: u32,
    count: u32,
}

struct RasterParams {
    // The atlas's side in texels.
    atlas: u32,
    items: u32,
    // The hardware pass's slope-scaled depth bias (shadow_raster's slope_bias).
    slope_bias: f32,
    _pad: u32,
}

@group(1) @binding(0) var<storage, read_write> shadow_keys: array<atomic<u32>>;
@group(1) @binding(1) var<storage, read> items: array<Item>;
@group(1) @binding(2) var<storage, read> raster: RasterParams;

// Clears the keys: 256 a workgroup, the workgroups in rows of num_workgroups.x.
@compute @workgroup_size(256)
fn cs_clear(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = id.y * groups.x * 256u + id.x;
    if i < arrayLength(&shadow_keys) {
        atomicStore(&shadow_keys[i], 0u);
    }
}

// The signed area of the parallelogram of a -> b and a -> p: which side of edge a b the
// point p lies on.
fn edge(a: vec2<f32>, b: vec2<f32>, p: vec2<f32>) -> f32 {
    return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
}

@compute @workgroup_size(64)
fn cs_shadow_raster(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lane: u32,
) {
    let k = group.y * groups.x + group.x;
    if k >= raster.items {
        return;
    }
    let item = items[k];
    if lane >= item.count {
        return;
    }
    let mesh = meshes[item.mesh];
    let view = shadow_views.views[item.view];
    let atlas = f32(raster.atlas);
    let origin = view.rect.xy * atlas;
    let side = view.rect.zw * atlas;
    // The corners in atlas texels (y down) and depth. The CPU kept only clusters wholly
    // between the depth planes, so w > 0 and 0 <= z <= w: nothing to clip.
    var p: array<vec2<f32>, 3>;
    var z: array<f32, 3>;
    for (var c = 0u; c < 3u; c++) {
        let position = pull_position(item.first_index + 3u * lane + c, mesh);
        let clip = view.clip_from_world * (mesh.model * vec4<f32>(position, 1.0));
        let ndc = clip.xyz / clip.w;
        p[c] = origin + vec2<f32>(0.5 * ndc.x + 0.5, 0.5 - 0.5 * ndc.y) * side;
        z[c] = ndc.z;
    }
    let area = edge(p[0], p[1], p[2]);
    if area == 0.0 {
        return;
    }
    // Texels whose centres the bounds hold, within the view's tile.
    let low = max(ceil(min(min(p[0], p[1]), p[2]) - 0.5), origin);
    let high = min(floor(max(max(p[0], p[1]), p[2]) - 0.5), origin + side - 1.0);
    if any(high < low) {
        return;
    }
    // The depth's plane: its change per texel across and down, and the slope-scaled
    // bias the hardware adds (wgpu's DepthBiasState::slope_scale: the larger change).
    let d1 = vec3<f32>(p[1] - p[0], z[1] - z[0]);
    let d2 = vec3<f32>(p[2] - p[0], z[2] - z[0]);
    let dz_dx = (d1.z * d2.y - d2.z * d1.y) / area;
    let dz_dy = (d2.z * d1.x - d1.z * d2.x) / area;
    let bias = raster.slope_bias * max(abs(dz_dx), abs(dz_dy));
    let width = raster.atlas;
    for (var y = low.y; y <= high.y; y += 1.0) {
        for (var x = low.x; x <= high.x; x += 1.0) {
            let centre = vec2<f32>(x + 0.5, y + 0.5);
            // Barycentric weights, each of the area's sign inside (edges included: a
            // texel on an edge both triangles share gets either's depth, which is one).
            let w0 = edge(p[1], p[2], centre) / area;
            let w1 = edge(p[2], p[0], centre) / area;
            let w2 = edge(p[0], p[1], centre) / area;
            if min(min(w0, w1), w2) < 0.0 {
                continue;
            }
            let depth = clamp(w0 * z[0] + w1 * z[1] + w2 * z[2] + bias, 0.0, 1.0);
            let texel = u32(y) * width + u32(x);
            atomicMax(&shadow_keys[texel], ~bitcast<u32>(depth));
        }
    }
}
