// The edge pass: a full-screen triangle shaded once per pixel that decides whether the
// pixel's samples differ. Edge pixels survive and the pipeline's stencil state writes 0x80
// into all their samples; other pixels are discarded and keep stencil 0.
// Composed after common.wgsl and gbuffer_read.wgsl.

// `compare`: samples differ when their view depths differ by more than this fraction of
// the larger one, ...
override DEPTH_THRESHOLD: f32 = 0.01;
// ... when the cosine between their normals is below this, ...
override NORMAL_THRESHOLD: f32 = 0.95;
// ... when an albedo channel differs by more than this, or when their flags differ.
override ALBEDO_THRESHOLD: f32 = 0.05;
// `centroid` / `coverage`: the edge bit of the material target's alpha to look for.
override EDGE_BIT: u32 = 0x80u;

fn differ(a: GSample, b: GSample) -> bool {
    let depth_step = abs(a.view_depth - b.view_depth) > DEPTH_THRESHOLD * max(a.view_depth, b.view_depth);
    let bend = dot(a.normal, b.normal) < NORMAL_THRESHOLD;
    let tint = any(abs(a.albedo - b.albedo) > vec3<f32>(ALBEDO_THRESHOLD));
    return depth_step || bend || tint || a.flags != b.flags;
}

@fragment
fn fs_compare(@builtin(position) position: vec4<f32>) {
    let pixel = pixel_of(position);
    let first = load_gsample(pixel, 0u);
    var edge = false;
    for (var s = 1u; s < SAMPLES; s++) {
        edge = edge || differ(first, load_gsample(pixel, s));
    }
    if !edge {
        discard;
    }
}

@fragment
fn fs_flag(@builtin(position) position: vec4<f32>) {
    let pixel = pixel_of(position);
    var edge = false;
    for (var s = 0u; s < SAMPLES; s++) {
        edge = edge || (material_flags(pixel, s).y & EDGE_BIT) != 0u;
    }
    if !edge {
        discard;
    }
}

// `all`: every pixel is shaded per sample.
@fragment
fn fs_all() {}
