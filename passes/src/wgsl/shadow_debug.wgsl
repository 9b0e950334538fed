// The shadow maps' debug views' colours (`--view shadows`, `--view cascades`), for the
// passes that draw them: light_tiled.wgsl's views of a G-buffer or a visibility buffer,
// forward_views.wgsl's of the forward pass. Composed after lighting.wgsl and shadow.wgsl
// (or shadow_none.wgsl).

// The shadows view's term: the visibility of the light whose maps come first in the
// atlas (the most important shadowed one, gpu_scene/shadows.rs) at surface `s`; 1
// where no light has maps.
fn first_shadow_visibility(s: Surface) -> f32 {
    for (var i = 0u; i < light_count(); i++) {
        if lights[i].shadow == 0u {
            return light_visibility(s, lights[i]);
        }
    }
    return 1.0;
}

// The cascades view's colour: which cascade of the first shadowed directional light holds
// surface `s` (red, green, blue, yellow from the nearest; grey past the last, or without
// such a light), darker where that light is shadowed.
fn cascade_color(s: Surface) -> vec3<f32> {
    let tints = array<vec3<f32>, 4>(
        vec3<f32>(1.0, 0.2, 0.2),
        vec3<f32>(0.2, 1.0, 0.2),
        vec3<f32>(0.25, 0.4, 1.0),
        vec3<f32>(1.0, 0.9, 0.2),
    );
    for (var i = 0u; i < light_count(); i++) {
        let c = shadow_cascade(s, lights[i]);
        if c != NO_CASCADE {
            return tints[min(c, 3u)] * (0.35 + 0.65 * light_visibility(s, lights[i]));
        }
    }
    return vec3<f32>(0.5);
}
