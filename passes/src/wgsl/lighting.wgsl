// The light a lit surface receives, for every pass that shades one: the deferred light
// passes (light.wgsl, light_tiled.wgsl) split it into what every pixel gets and the
// point and spot lights they cull; forward passes add it all at once.
// Composed after common.wgsl, scene.wgsl and brdf.wgsl, and with shadow.wgsl or
// shadow_none.wgsl (`light_visibility`).

// Image-based lighting from scene.wgsl's environment_tex and split_sum_tex.

// Whether the scene has an environment (variant.rs; the default is the general
// shader). Without one its irradiance and intensity are zero: the code would add zero.
override ENVIRONMENT: bool = true;

fn environment_irradiance(n: vec3<f32>) -> vec3<f32> {
    // Spelled out with constant indices: a loop over local arrays would make the compiler
    // keep them in (slow) indexable memory.
    let c = &light_info.irradiance;
    let e = (*c)[0].rgb + (*c)[1].rgb * n.y + (*c)[2].rgb * n.z + (*c)[3].rgb * n.x
        + (*c)[4].rgb * (n.x * n.y) + (*c)[5].rgb * (n.y * n.z)
        + (*c)[6].rgb * (3.0 * n.z * n.z - 1.0) + (*c)[7].rgb * (n.x * n.z)
        + (*c)[8].rgb * (n.x * n.x - n.y * n.y);
    return max(e, vec3<f32>(0.0));
}

// The environment's light reflected toward the viewer (Karis's split sum): diffuse from
// the irradiance, weighted by what the specular lobe leaves (as brdf.wgsl's (1 - F)),
// plus the prefiltered radiance around the reflection times the BRDF's directional albedo.
// Explicit mip levels: valid in compute and non-uniform control flow alike.
fn environment_light(s: Surface) -> vec3<f32> {
    let n_v = clamp(dot(s.normal, s.view), 1e-4, 1.0);
    let split = textureSampleLevel(split_sum_tex, environment_sampler, vec2<f32>(n_v, s.roughness), 0.0).rg;
    let reflected = reflectance(s);
    let specular_albedo = reflected.f0 * split.x + reflected.f90 * split.y;
    let prefiltered = prefiltered_radiance(reflect(-s.view, s.normal), s.roughness);
    let diffuse = environment_irradiance(s.normal) / PI * s.albedo * (1.0 - s.metallic) * (1.0 - specular_albedo);
    var base = diffuse + prefiltered * specular_albedo;
    if has_sheen(s) {
        base = sheen_environment(s, base, n_v);
    }
    if CLEARCOAT && s.layers.clearcoat > 0.0 {
        return coated_environment(s, base);
    }
    return base;
}

// `base`, the environment's light on surface `s`, under its sheen seen at `n_v`: scaled by
// what the sheen leaves, plus the sheen's reflection: its albedo times the prefiltered
// radiance around the reflection at the sheen's roughness (the GGX-prefiltered map
// standing in for the sample viewer's Charlie-prefiltered one).
fn sheen_environment(s: Surface, base: vec3<f32>, n_v: f32) -> vec3<f32> {
    let c = s.layers.sheen_color;
    let roughness = s.layers.sheen_roughness;
    let albedo = sheen_albedo(n_v, roughness);
    let prefiltered = prefiltered_radiance(reflect(-s.view, s.normal), roughness);
    return base * (1.0 - max(c.r, max(c.g, c.b)) * albedo) + prefiltered * c * albedo;
}

// `base`, the environment's light on surface `s`, under its clear coat: the coat's
// prefiltered radiance around its own reflection, times its lobe's directional albedo
// without Fresnel (the split sum's scale plus bias: coated() weighs it by the coat's
// Fresnel).
fn coated_environment(s: Surface, base: vec3<f32>) -> vec3<f32> {
    let n = s.layers.clearcoat_normal;
    let roughness = s.layers.clearcoat_roughness;
    let n_v = clamp(dot(n, s.view), 1e-4, 1.0);
    let split = textureSampleLevel(split_sum_tex, environment_sampler, vec2<f32>(n_v, roughness), 0.0).rg;
    let prefiltered = prefiltered_radiance(reflect(-s.view, n), roughness);
    return coated(s, base, prefiltered * (split.x + split.y));
}

// The environment's radiance around `direction`, prefiltered with the GGX lobe of
// `roughness` (the cube map's mip level for it).
fn prefiltered_radiance(direction: vec3<f32>, roughness: f32) -> vec3<f32> {
    let level = clamp(roughness, 0.0, 1.0) * light_info.environment_max_level;
    return textureSampleLevel(environment_tex, environment_sampler, direction, level).rgb * light_info.environment_intensity;
}

// Light from everywhere: the ambient term and the environment, scaled by the material's
// occlusion.
fn ambient_light(s: Surface) -> vec3<f32> {
    var color = light_info.ambient * s.albedo;
    if ENVIRONMENT {
        color += environment_light(s);
    }
    return color * s.occlusion;
}

// The light `light` sends surface `s`, as far as its shadow map lets it through
// (`light_visibility`: shadow.wgsl, or shadow_none.wgsl where the pass reads no atlas).
fn direct_light(s: Surface, light: LightData) -> vec3<f32> {
    let color = shade_light(s, light);
    if all(color == vec3<f32>(0.0)) {
        return color;
    }
    return color * light_visibility(s, light);
}

// The light that reaches every surface: ambient plus every directional light.
fn ambient_and_directional(s: Surface) -> vec3<f32> {
    var color = ambient_light(s);
    // brdf.wgsl's DIRECTIONAL_LIGHTS: without directional lights that emit, the loop
    // would add zeros.
    if DIRECTIONAL_LIGHTS {
        for (var i = 0u; i < directional_count(); i++) {
            color += direct_light(s, lights[i]);
        }
    }
    return color;
}

// Every light of the scene, for passes that shade a surface once with all of them.
fn every_light(s: Surface) -> vec3<f32> {
    var color = ambient_light(s);
    for (var i = 0u; i < light_count(); i++) {
        color += direct_light(s, lights[i]);
    }
    return color;
}
