// The forward pass's debug views of the shadow maps (passes/forward.rs, `view: shadows`
// or `cascades`), as light_tiled.wgsl draws them from a G-buffer: each fragment's
// shadow_debug.wgsl colour at its surface, once per pixel; grey where the material is
// unlit. Composed after forward.wgsl and shadow_debug.wgsl.

@fragment
fn fs_shadows_view(in: PixelVaryings, @builtin(front_facing) front: bool) -> @location(0) vec4<f32> {
    return view_color(in, front, false);
}

@fragment
fn fs_cascades_view(in: PixelVaryings, @builtin(front_facing) front: bool) -> @location(0) vec4<f32> {
    return view_color(in, front, true);
}

// The view's colour of the fragment `in`: its cascade's, or its visibility term as grey.
fn view_color(in: PixelVaryings, front: bool, cascades: bool) -> vec4<f32> {
    let f = fragment_of(pixel_attributes(in, front), front);
    if f.unlit {
        return vec4<f32>(0.5, 0.5, 0.5, 1.0);
    }
    if cascades {
        return vec4<f32>(cascade_color(f.s), 1.0);
    }
    return vec4<f32>(vec3<f32>(first_shadow_visibility(f.s)), 1.0);
}
