// The edge pass: a full-screen triangle shaded once per pixel that decides whether the
// pixel's samples differ (edge_detect.wgsl). Edge pixels survive and the pipeline's
// stencil state writes 0x80 into all their samples; other pixels are discarded and keep
// stencil 0.
// Composed after common.wgsl, gbuffer_read.wgsl and edge_detect.wgsl.

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
