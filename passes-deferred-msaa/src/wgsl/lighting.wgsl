// The light a lit surface receives, for every pass that shades one: the deferred light
// passes (light.wgsl, light_tiled.wgsl) split it into what every pixel gets and the
// point and spot lights they cull; forward passes add it all at once.
// Composed after common.wgsl, scene.wgsl and brdf.wgsl.

// Light from everywhere: the ambient term, scaled by the material's occlusion.
fn ambient_light(s: Surface) -> vec3<f32> {
    return light_info.ambient * s.albedo * s.occlusion;
}

// The light that reaches every surface: ambient plus every directional light.
fn ambient_and_directional(s: Surface) -> vec3<f32> {
    var color = ambient_light(s);
    // brdf.wgsl's DIRECTIONAL_LIGHTS: without directional lights that emit, the loop
    // would add zeros.
    if DIRECTIONAL_LIGHTS {
        for (var i = 0u; i < light_info.directional_count; i++) {
            color += shade_light(s, lights[i]);
        }
    }
    return color;
}

// Every light of the scene, for passes that shade a surface once with all of them.
fn every_light(s: Surface) -> vec3<f32> {
    var color = ambient_light(s);
    for (var i = 0u; i < light_info.light_count; i++) {
        color += shade_light(s, lights[i]);
    }
    return color;
}
