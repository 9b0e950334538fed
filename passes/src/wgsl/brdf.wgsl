// Lambert diffuse plus GGX / height-correlated Smith / Schlick specular (glTF
// metallic-roughness) with the layers of KHR_materials_ior and _specular (the dielectric
// specular's F0 and weight), _sheen (a Charlie lobe over the base) and _clearcoat (a
// second GGX lobe over both), and the KHR_lights_punctual falloffs. Every denominator is
// kept positive, so no input produces NaN or Inf.

struct Surface {
    // Camera-relative world position; the camera is at the origin.
    position: vec3<f32>,
    normal: vec3<f32>,
    view: vec3<f32>,
    albedo: vec3<f32>,
    metallic: f32,
    roughness: f32,
    // Ambient occlusion: scales the ambient term (light from everywhere, which crevices
    // block), never a punctual light's.
    occlusion: f32,
    // What the material's extensions add (common.wgsl).
    layers: Layers,
}

// The parts of the BRDF that depend on the geometry and roughness only, not on the
// albedo or metalness: what a light pre-pass accumulates before the material is known
// (light_prepass.wgsl).
struct Lobe {
    // The cosine factor; the light is below the surface when it is not positive.
    n_l: f32,
    // GGX distribution times the height-correlated Smith visibility.
    specular: f32,
    // Schlick's weight (1 - v.h)^5: Fresnel is f0 + (1 - f0) * schlick.
    schlick: f32,
}

fn lobe(s: Surface, l: vec3<f32>) -> Lobe {
    return lobe_at(s.normal, s.view, s.roughness, l);
}

// The lobe of a surface of unit `normal` and perceptual `roughness` seen from `view`.
fn lobe_at(normal: vec3<f32>, view: vec3<f32>, roughness: f32, l: vec3<f32>) -> Lobe {
    let n_l = dot(normal, l);
    if n_l <= 0.0 {
        return Lobe(n_l, 0.0, 0.0);
    }
    let h = safe_normalize(l + view);
    let n_v = max(dot(normal, view), 1e-4);
    let n_h = clamp(dot(normal, h), 0.0, 1.0);
    let v_h = clamp(dot(view, h), 0.0, 1.0);
    let alpha = max(roughness, 0.045);
    let a2 = alpha * alpha * alpha * alpha;
    let d_denominator = n_h * n_h * (a2 - 1.0) + 1.0;
    let distribution = a2 / (PI * d_denominator * d_denominator);
    let visibility = 0.5 / (n_l * sqrt(n_v * n_v * (1.0 - a2) + a2) + n_v * sqrt(n_l * n_l * (1.0 - a2) + a2));
    return Lobe(n_l, distribution * visibility, pow(1.0 - v_h, 5.0));
}

// A surface's specular reflectance facing the viewer (F0) and at grazing angles (F90):
// glTF's mix by metalness of a dielectric's (F0 0.04, F90 1 in the core model) and a
// metal's (its albedo, 1). KHR_materials_ior and _specular give the dielectric another F0
// (layers.specular_f0) and scale its F0 and F90 by their weight (layers.specular), as
// the glTF sample viewer's dielectric Fresnel does. Without them (no SPECULAR) the
// arithmetic is the core model's exactly.
struct Reflectance {
    f0: vec3<f32>,
    f90: f32,
}

fn reflectance(s: Surface) -> Reflectance {
    var f0 = vec3<f32>(0.04);
    var weight = 1.0;
    if SPECULAR {
        f0 = s.layers.specular_f0;
        weight = s.layers.specular;
    }
    return Reflectance(mix(f0 * weight, s.albedo, s.metallic), weight + (1.0 - weight) * s.metallic);
}

// Schlick's Fresnel of `r` for the weight `schlick` (Lobe's).
fn fresnel(r: Reflectance, schlick: f32) -> vec3<f32> {
    return r.f0 + (r.f90 - r.f0) * schlick;
}

fn brdf_times_cosine(s: Surface, l: vec3<f32>) -> vec3<f32> {
    let k = lobe(s, l);
    var color = vec3<f32>(0.0);
    if k.n_l > 0.0 {
        let f = fresnel(reflectance(s), k.schlick);
        let diffuse = (1.0 - f) * (1.0 - s.metallic) * s.albedo / PI;
        color = (diffuse + k.specular * f) * k.n_l;
        if has_sheen(s) {
            color = color * sheen_scaling(s, k.n_l) + sheen_lobe(s, l) * k.n_l;
        }
    }
    if CLEARCOAT && s.layers.clearcoat > 0.0 {
        let coat = lobe_at(s.layers.clearcoat_normal, s.view, s.layers.clearcoat_roughness, l);
        color = coated(s, color, vec3<f32>(coat.specular * max(coat.n_l, 0.0)));
    }
    return color;
}

// KHR_materials_sheen: whether surface `s` has a sheen (its colour is not black).
fn has_sheen(s: Surface) -> bool {
    let c = s.layers.sheen_color;
    return SHEEN && max(c.r, max(c.g, c.b)) > 0.0;
}

// The sheen lobe of `s` toward light `l`: Estevez and Kulla's Charlie distribution with
// the visibility term of their fitted Λ (the glTF sample viewer's), times the sheen
// colour; scene/src/sheen.rs evaluates the same functions for sheen_albedo's table.
fn sheen_lobe(s: Surface, l: vec3<f32>) -> vec3<f32> {
    let n_l = clamp(dot(s.normal, l), 0.0, 1.0);
    let n_v = clamp(dot(s.normal, s.view), 1e-4, 1.0);
    let n_h = clamp(dot(s.normal, safe_normalize(l + s.view)), 0.0, 1.0);
    let roughness = max(s.layers.sheen_roughness, 1e-6);
    let alpha = roughness * roughness;
    let sin2 = 1.0 - n_h * n_h;
    let distribution = (2.0 + 1.0 / alpha) * pow(sin2, 0.5 / alpha) / (2.0 * PI);
    let visibility = clamp(1.0 / ((1.0 + sheen_lambda(n_v, alpha) + sheen_lambda(n_l, alpha)) * 4.0 * n_v * max(n_l, 1e-4)), 0.0, 1.0);
    return s.layers.sheen_color * distribution * visibility;
}

// Estevez and Kulla's Λ of the sheen's masking at cosine `cos` for α `alpha`.
fn sheen_lambda(cos: f32, alpha: f32) -> f32 {
    if cos < 0.5 {
        return exp(sheen_lambda_exponent(cos, alpha));
    }
    return exp(2.0 * sheen_lambda_exponent(0.5, alpha) - sheen_lambda_exponent(1.0 - cos, alpha));
}

fn sheen_lambda_exponent(x: f32, alpha: f32) -> f32 {
    let t = (1.0 - alpha) * (1.0 - alpha);
    let a = mix(21.5473, 25.3245, t);
    let b = mix(3.82987, 3.32435, t);
    let c = mix(0.19823, 0.16801, t);
    let d = mix(-1.97760, -1.27393, t);
    let e = mix(-4.32054, -4.85967, t);
    return a / (1.0 + b * pow(x, c)) + d * x + e;
}

// The directional albedo of the sheen lobe of colour 1 seen or lit at cosine `cos`
// (scene/src/sheen.rs's table, in the split-sum lookup table's blue channel).
fn sheen_albedo(cos: f32, roughness: f32) -> f32 {
    return textureSampleLevel(split_sum_tex, environment_sampler, vec2<f32>(cos, roughness), 0.0).b;
}

// What the sheen of `s` leaves of the base lit from `n_l`: the extension's albedo
// scaling, 1 - max(colour) E (sheen_taken's E).
fn sheen_scaling(s: Surface, n_l: f32) -> f32 {
    let c = s.layers.sheen_color;
    return 1.0 - max(c.r, max(c.g, c.b)) * sheen_taken(s, n_l);
}

// E of the albedo scaling of the sheen of `s` lit from `n_l`: the albedo of its lobe of
// colour 1 toward the viewer or the light, whichever takes more.
fn sheen_taken(s: Surface, n_l: f32) -> f32 {
    let r = s.layers.sheen_roughness;
    let n_v = clamp(dot(s.normal, s.view), 0.0, 1.0);
    return max(sheen_albedo(n_v, r), sheen_albedo(n_l, r));
}

// KHR_materials_clearcoat: how much of the light the coat of `layers` reflects toward
// `view`: its strength times its Fresnel, a dielectric of index 1.5 (F0 0.04) at its own
// normal's angle to the view (the extension's fresnel_coat, which has no half vector).
// 0 without a coat.
fn coat_weight(layers: Layers, view: vec3<f32>) -> f32 {
    if !CLEARCOAT || layers.clearcoat <= 0.0 {
        return 0.0;
    }
    let n_v = clamp(dot(layers.clearcoat_normal, view), 0.0, 1.0);
    return layers.clearcoat * (0.04 + 0.96 * pow(1.0 - n_v, 5.0));
}

// `base`, the light surface `s` reflects under its coat, with the coat's `reflected` on
// top (its GGX lobe times the cosine, for light; or its split sum, for the environment):
// mix(base, reflected, coat_weight), so the coat takes from the base what it reflects.
fn coated(s: Surface, base: vec3<f32>, reflected: vec3<f32>) -> vec3<f32> {
    let weight = coat_weight(s.layers, s.view);
    return base * (1.0 - weight) + reflected * weight;
}

// Which light kinds the scene has (variant.rs): a pipeline for a scene without
// a kind sets its constant false and the driver compiles that kind's code out. A light
// of an absent kind emits nothing (zero radiance), so it adds zero through either code.
// The defaults are the general shader.
override DIRECTIONAL_LIGHTS: bool = true;
override POINT_LIGHTS: bool = true;
override SPOT_LIGHTS: bool = true;

// Where a light's radiance arrives from at surface point `p` (unit `l`, toward the light)
// and the fraction of it that arrives (`attenuation`: 1 for directional lights).
struct Incident {
    l: vec3<f32>,
    attenuation: f32,
}

fn incident(p: vec3<f32>, light: LightData) -> Incident {
    if DIRECTIONAL_LIGHTS && light.kind == LIGHT_DIRECTIONAL {
        return Incident(-light.direction, 1.0);
    }
    if !(POINT_LIGHTS || SPOT_LIGHTS) {
        return Incident(vec3<f32>(0.0, 0.0, 1.0), 0.0);
    }
    let to_light = light.position - p;
    let distance2 = max(dot(to_light, to_light), 1e-8);
    let distance = sqrt(distance2);
    let l = to_light / distance;
    // glTF's recommended window: smooth, and exactly zero at the range.
    let ratio = distance / max(light.range, 1e-20);
    let window = clamp(1.0 - ratio * ratio * ratio * ratio, 0.0, 1.0);
    var attenuation = window * window / distance2;
    if SPOT_LIGHTS && light.kind == LIGHT_SPOT {
        let cone = clamp(dot(light.direction, -l) * light.spot_scale + light.spot_offset, 0.0, 1.0);
        attenuation *= cone * cone;
    }
    return Incident(l, attenuation);
}

// Radiance arriving from `light` at the surface, times the BRDF and cosine.
fn shade_light(s: Surface, light: LightData) -> vec3<f32> {
    let i = incident(s.position, light);
    return brdf_times_cosine(s, i.l) * light.radiance * i.attenuation;
}

// Whether `light` reaches point `p` at all (the `lights` debug view counts these).
fn reaches(light: LightData, p: vec3<f32>) -> bool {
    if light.kind == LIGHT_DIRECTIONAL {
        return true;
    }
    let to_light = light.position - p;
    if dot(to_light, to_light) >= light.range * light.range {
        return false;
    }
    return light.kind != LIGHT_SPOT || dot(light.direction, -safe_normalize(to_light)) * light.spot_scale + light.spot_offset > 0.0;
}
