// The edge pass: a full-screen triangle shaded once per pixel that decides whether the
// pixel's samples differ (edge_detect.wgsl). Edge pixels survive and the pipeline's
// stencil state writes 0x80 into all their samples; other pixels are discarded and keep
// stencil 0.
// Composed after common.wgsl, gbuffer_read.wgsl and edge_detect.wgsl.

// `compare`: some sample of `pixel` differs from sample 0.
fn samples_differ(pixel: vec2<i32>) -> bool {
    let first = load_gsample(pixel, 0u);
    var edge = false;
    for (var s = 1u; s < SAMPLES; s++) {
        edge = edge || differ(first, load_gsample(pixel, s));
    }
    return edge;
}

// `centroid` / `coverage`: some sample's fragment recorded EDGE_BIT.
fn edge_bit_set(pixel: vec2<i32>) -> bool {
    var edge = false;
    for (var s = 0u; s < SAMPLES; s++) {
        edge = edge || (material_flags(pixel, s).y & EDGE_BIT) != 0u;
    }
    return edge;
}

@fragment
fn fs_compare(@builtin(position) position: vec4<f32>) {
    if !samples_differ(pixel_of(position)) {
        discard;
    }
}

@fragment
fn fs_flag(@builtin(position) position: vec4<f32>) {
    if !edge_bit_set(pixel_of(position)) {
        discard;
    }
}

// `all`: every pixel is shaded per sample.
@fragment
fn fs_all() {}
