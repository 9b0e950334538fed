// FXAA 3.11 (Timothy Lottes, NVIDIA 2011), the PC "quality" variant, on the tone-mapped
// image. Composed after common.wgsl and a generated block that defines `FXAA_STEPS`, the
// search steps of the chosen quality preset (passes/fxaa.rs). Inputs are group 1, like
// every deferred pass's: the image, read through a linear clamp-to-edge sampler, because
// the algorithm's taps between texels average two rows (or two columns) in one fetch.
//
// The structure and names follow FxaaPixelShader of Fxaa3_11.h so the two can be read side
// by side; the unrolled search loop is a loop over FXAA_STEPS.

@group(1) @binding(0) var ldr_tex: texture_2d<f32>;
@group(1) @binding(1) var ldr_sampler: sampler;

// FXAA's fxaaQualitySubpix: how much sub-pixel aliasing is removed (0 none, 1 softest).
override SUBPIX: f32 = 0.75;
// fxaaQualityEdgeThreshold: the local contrast, relative to the brightest luma around,
// below which a pixel is left alone.
override EDGE_THRESHOLD: f32 = 0.166;
// fxaaQualityEdgeThresholdMin: the absolute contrast below which dark pixels are left
// alone.
override EDGE_THRESHOLD_MIN: f32 = 0.0833;

// Whether the sampler returns linear colour: an sRGB texture (true) decodes on reads, an
// rgba8unorm one holds the encoded values.
override LINEAR_INPUT: bool = true;

// FXAA wants perceptual luma. From linear colour, the square root of its linear luma
// approximates the encoded one (Fxaa3_11.h's suggestion for linear input).
fn fxaa_luma(rgb: vec3<f32>) -> f32 {
    let luma = dot(rgb, vec3<f32>(0.299, 0.587, 0.114));
    return select(luma, sqrt(luma), LINEAR_INPUT);
}

fn fxaa_tap(uv: vec2<f32>) -> vec3<f32> {
    return textureSampleLevel(ldr_tex, ldr_sampler, uv, 0.0).rgb;
}

fn luma_at(uv: vec2<f32>) -> f32 {
    return fxaa_luma(fxaa_tap(uv));
}

// The luma `dx`, `dy` texels from `uv` (FxaaTexOff).
fn luma_off(uv: vec2<f32>, dx: f32, dy: f32, rcp_frame: vec2<f32>) -> f32 {
    return luma_at(uv + vec2<f32>(dx, dy) * rcp_frame);
}

@fragment
fn fs_fxaa(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let rcp_frame = 1.0 / vec2<f32>(textureDimensions(ldr_tex));
    var pos_m = position.xy * rcp_frame;
    let rgb_m = fxaa_tap(pos_m);
    let luma_m = fxaa_luma(rgb_m);
    var luma_s = luma_off(pos_m, 0.0, 1.0, rcp_frame);
    let luma_e = luma_off(pos_m, 1.0, 0.0, rcp_frame);
    var luma_n = luma_off(pos_m, 0.0, -1.0, rcp_frame);
    let luma_w = luma_off(pos_m, -1.0, 0.0, rcp_frame);

    let range_max = max(max(luma_n, luma_w), max(luma_e, max(luma_s, luma_m)));
    let range_min = min(min(luma_n, luma_w), min(luma_e, min(luma_s, luma_m)));
    let range = range_max - range_min;
    // Too little contrast: not an edge, the pixel is returned as it is.
    if range < max(EDGE_THRESHOLD_MIN, range_max * EDGE_THRESHOLD) {
        return vec4<f32>(rgb_m, 1.0);
    }

    let luma_nw = luma_off(pos_m, -1.0, -1.0, rcp_frame);
    let luma_se = luma_off(pos_m, 1.0, 1.0, rcp_frame);
    let luma_ne = luma_off(pos_m, 1.0, -1.0, rcp_frame);
    let luma_sw = luma_off(pos_m, -1.0, 1.0, rcp_frame);

    // Is the local edge horizontal or vertical?
    let luma_ns = luma_n + luma_s;
    let luma_we = luma_w + luma_e;
    let subpix_rcp_range = 1.0 / range;
    let subpix_nswe = luma_ns + luma_we;
    let edge_horz1 = -2.0 * luma_m + luma_ns;
    let edge_vert1 = -2.0 * luma_m + luma_we;
    let luma_nese = luma_ne + luma_se;
    let luma_nwne = luma_nw + luma_ne;
    let edge_horz2 = -2.0 * luma_e + luma_nese;
    let edge_vert2 = -2.0 * luma_n + luma_nwne;
    let luma_nwsw = luma_nw + luma_sw;
    let luma_swse = luma_sw + luma_se;
    let edge_horz4 = abs(edge_horz1) * 2.0 + abs(edge_horz2);
    let edge_vert4 = abs(edge_vert1) * 2.0 + abs(edge_vert2);
    let edge_horz3 = -2.0 * luma_w + luma_nwsw;
    let edge_vert3 = -2.0 * luma_s + luma_swse;
    let edge_horz = abs(edge_horz3) + edge_horz4;
    let edge_vert = abs(edge_vert3) + edge_vert4;
    let subpix_nwswnese = luma_nwsw + luma_nese;
    let horz_span = edge_horz >= edge_vert;
    var length_sign = select(rcp_frame.x, rcp_frame.y, horz_span);
    let subpix_a = subpix_nswe * 2.0 + subpix_nwswnese;
    if !horz_span {
        luma_n = luma_w;
        luma_s = luma_e;
    }
    let subpix_b = subpix_a * (1.0 / 12.0) - luma_m;

    // Which side of the pixel the edge is on: the neighbour with the steeper gradient.
    let gradient_n = luma_n - luma_m;
    let gradient_s = luma_s - luma_m;
    var luma_nn = luma_n + luma_m;
    let luma_ss = luma_s + luma_m;
    let pair_n = abs(gradient_n) >= abs(gradient_s);
    let gradient = max(abs(gradient_n), abs(gradient_s));
    if pair_n {
        length_sign = -length_sign;
    }
    let subpix_c = clamp(abs(subpix_b) * subpix_rcp_range, 0.0, 1.0);

    // Search both ways along the edge, half a texel toward its other side, for its ends:
    // where the luma pair's average leaves the edge's by a quarter of the gradient.
    var pos_b = pos_m;
    let off_np = select(vec2<f32>(0.0, rcp_frame.y), vec2<f32>(rcp_frame.x, 0.0), horz_span);
    if horz_span {
        pos_b.y += length_sign * 0.5;
    } else {
        pos_b.x += length_sign * 0.5;
    }
    var pos_n = pos_b - off_np * FXAA_STEPS[0];
    var pos_p = pos_b + off_np * FXAA_STEPS[0];
    let subpix_d = -2.0 * subpix_c + 3.0;
    var luma_end_n = luma_at(pos_n);
    let subpix_e = subpix_c * subpix_c;
    var luma_end_p = luma_at(pos_p);
    if !pair_n {
        luma_nn = luma_ss;
    }
    let gradient_scaled = gradient * 0.25;
    let luma_mm = luma_m - luma_nn * 0.5;
    let subpix_f = subpix_d * subpix_e;
    let luma_m_lt_zero = luma_mm < 0.0;
    luma_end_n -= luma_nn * 0.5;
    luma_end_p -= luma_nn * 0.5;
    var done_n = abs(luma_end_n) >= gradient_scaled;
    var done_p = abs(luma_end_p) >= gradient_scaled;
    if !done_n {
        pos_n -= off_np * FXAA_STEPS[1];
    }
    if !done_p {
        pos_p += off_np * FXAA_STEPS[1];
    }
    for (var i = 2u; i < FXAA_STEP_COUNT; i++) {
        if done_n && done_p {
            break;
        }
        if !done_n {
            luma_end_n = luma_at(pos_n) - luma_nn * 0.5;
        }
        if !done_p {
            luma_end_p = luma_at(pos_p) - luma_nn * 0.5;
        }
        done_n = abs(luma_end_n) >= gradient_scaled;
        done_p = abs(luma_end_p) >= gradient_scaled;
        if !done_n {
            pos_n -= off_np * FXAA_STEPS[i];
        }
        if !done_p {
            pos_p += off_np * FXAA_STEPS[i];
        }
    }

    // How far along the span the pixel lies sets how far its sample moves across the
    // edge; only the nearer end counts, and only if the luma changes the right way there.
    var dst_n = pos_m.x - pos_n.x;
    var dst_p = pos_p.x - pos_m.x;
    if !horz_span {
        dst_n = pos_m.y - pos_n.y;
        dst_p = pos_p.y - pos_m.y;
    }
    let good_span_n = (luma_end_n < 0.0) != luma_m_lt_zero;
    let span_length = dst_p + dst_n;
    let good_span_p = (luma_end_p < 0.0) != luma_m_lt_zero;
    let span_length_rcp = 1.0 / span_length;
    let direction_n = dst_n < dst_p;
    let dst = min(dst_n, dst_p);
    let good_span = select(good_span_p, good_span_n, direction_n);
    let subpix_g = subpix_f * subpix_f;
    let pixel_offset = -dst * span_length_rcp + 0.5;
    let subpix_h = subpix_g * SUBPIX;
    let pixel_offset_good = select(0.0, pixel_offset, good_span);
    let pixel_offset_subpix = max(pixel_offset_good, subpix_h);
    if horz_span {
        pos_m.y += pixel_offset_subpix * length_sign;
    } else {
        pos_m.x += pixel_offset_subpix * length_sign;
    }
    return vec4<f32>(fxaa_tap(pos_m), 1.0);
}
