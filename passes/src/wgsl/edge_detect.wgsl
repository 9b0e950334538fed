// Edge detection: whether two samples hold different surfaces. One definition for the
// fragment path (edge.wgsl, which marks the stencil) and the tiled compute pass
// (light_tiled.wgsl), so both classify every pixel alike.
// Composed after common.wgsl.

// `compare`: samples differ when their view depths differ by more than this fraction of
// the larger one, ...
override DEPTH_THRESHOLD: f32 = 0.01;
// ... when the cosine between their normals is below this, ...
override NORMAL_THRESHOLD: f32 = 0.95;
// ... when an albedo channel differs by more than this, or when their flags differ.
override ALBEDO_THRESHOLD: f32 = 0.05;
// `centroid` / `coverage`: the edge bit of the material target's alpha to look for.
override EDGE_BIT: u32 = 0x80u;

// Whether view depths `a` and `b` differ by more than DEPTH_THRESHOLD of the larger: a
// step between surfaces, not one surface's slope across a pixel.
fn depth_step(a: f32, b: f32) -> bool {
    return abs(a - b) > DEPTH_THRESHOLD * max(a, b);
}

// Whether two samples hold different surfaces, by the `compare` thresholds.
fn differ(a: GSample, b: GSample) -> bool {
    let depth_step = depth_step(a.view_depth, b.view_depth);
    let bend = dot(a.normal, b.normal) < NORMAL_THRESHOLD;
    let tint = any(abs(a.albedo - b.albedo) > vec3<f32>(ALBEDO_THRESHOLD));
    return depth_step || bend || tint || a.flags != b.flags;
}
