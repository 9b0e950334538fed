// The view depth the G-buffer stored: its `view_depth` channel (group 1, binding 3).
// Passes that attach the depth-stencil while reading the G-buffer need it; the lean
// G-buffer has none, and its tiled pass composes view_depth_from_depth.wgsl instead.

@group(1) @binding(3) var view_depth_tex: GTexF;

// Interpolated at the fragment's centroid, so every sample of one fragment has the same.
const STORED_VIEW_DEPTH: bool = true;

fn load_view_depth(pixel: vec2<i32>, s: u32) -> f32 {
    return textureLoad(view_depth_tex, pixel, s).r;
}
