// G-buffer samples as surfaces to light, for the fragment light passes (light.wgsl) and
// the tiled compute pass (light_tiled.wgsl), so both place and light a sample alike.
// Composed after common.wgsl, scene.wgsl, gbuffer_read.wgsl and brdf.wgsl.

// Per-sample shading: the sample's surface point is where the rasterizer tested it
// against the light volume, the sample's depth at the sample's position. (The G-buffer's
// view depth is the fragment's, interpolated at its centroid: on steep surfaces it can
// lie far from a sample the volume test rejected.)
fn sample_surface(pixel: vec2<i32>, s: u32) -> vec3<f32> {
    return unproject(sample_position(pixel, s), sample_depth(pixel, s));
}

// Per-pixel shading: the surface at the pixel center, at sample `s`'s view depth.
fn center_surface(pixel: vec2<i32>, s: u32) -> vec3<f32> {
    return surface_position(vec2<f32>(pixel) + 0.5, load_view_depth(pixel, s));
}

// G-buffer sample `g` as the surface point `p` (camera-relative) seen from the camera.
fn surface_of(g: GSample, p: vec3<f32>) -> Surface {
    return Surface(p, g.normal, safe_normalize(-p), g.albedo, g.metallic, g.roughness, g.occlusion, g.layers);
}
