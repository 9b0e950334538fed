// The light pre-pass's `shade_sample` for light.wgsl: the light a thin G-buffer sample
// receives, before its material is known, added to the light buffer (passes/
// light_prepass.rs), and what its clear coat and sheen receive, added to the lobes
// buffer where the pass has one. Composed after surface.wgsl; `light` is a light's index
// or light.wgsl's ALL_DIRECTIONAL. The thin G-buffer has normals, view depth, the
// material target's roughness and flags (its metalness is never read here) and, for a
// scene with coats or sheens, their layers (gbuffer_layers.wgsl).
//
// For each light of radiance c (attenuated, times the cosine) brdf.wgsl's shading is
//   diffuse  (1 - f0) (1 - metallic) albedo / pi  *  c (1 - schlick)
//   specular D V (f0 + (1 - f0) schlick)  *  c
// The light buffer keeps, summed over lights:
//   rgb: c (1 - schlick), the diffuse light: exact for any albedo and f0, which factor out;
//   a:   the luminance of a dielectric's specular, D V (0.04 + 0.96 schlick) c.
// The lobes buffer keeps, summed over lights, luminances the material pass colours with
// the diffuse light's chroma, as it colours the specular:
//   r: the clear coat's lobe, D V of the coat's normal and roughness times its own
//      cosine (the material pass weighs it by the coat's Fresnel, which needs no light);
//   g: the sheen's lobe of colour 1, the Charlie D V times the cosine;
//   b: the diffuse light times the sheen's E (brdf.wgsl's sheen_taken): over the diffuse
//      light's luminance, the mean E by which the sheen dims the base.
// The material pass (light_prepass_material.wgsl) colours the specular with the diffuse
// light's chroma and scales its Fresnel to the surface's f0, so it is exact for
// dielectrics under white light and approximate for metals and coloured light: the
// classic light pre-pass trade of one specular channel for a thinner light buffer.

fn light_terms(s: Surface, light: LightData) -> SampleLight {
    let none = vec4<f32>(0.0);
    var out = SampleLight(none, none);
    let i = incident(s.position, light);
    let k = lobe(s, i.l);
    let coated = CLEARCOAT && s.layers.clearcoat > 0.0;
    if k.n_l <= 0.0 && !coated {
        return out;
    }
    // As far as its shadow map lets it through (shadow.wgsl, or shadow_none.wgsl where the
    // pass reads no atlas), as lighting.wgsl's direct_light scales it.
    let visibility = light_visibility(s, light);
    if k.n_l > 0.0 {
        let c = light.radiance * i.attenuation * k.n_l * visibility;
        let dielectric = k.specular * (0.04 + (1.0 - 0.04) * k.schlick);
        let diffuse = c * (1.0 - k.schlick);
        out.light = vec4<f32>(diffuse, luminance(c) * dielectric);
        if has_sheen(s) {
            var unit = s;
            unit.layers.sheen_color = vec3<f32>(1.0);
            let sheen = luminance(c) * sheen_lobe(unit, i.l).r;
            out.lobes = vec4<f32>(0.0, sheen, luminance(diffuse) * sheen_taken(s, k.n_l), 0.0);
        }
    }
    if coated {
        let coat = lobe_at(s.layers.clearcoat_normal, s.view, s.layers.clearcoat_roughness, i.l);
        let c = light.radiance * i.attenuation * max(coat.n_l, 0.0) * visibility;
        out.lobes.r = luminance(c) * coat.specular;
    }
    return out;
}

// The light sample `s` of `pixel`, the surface point `p` (camera-relative), receives.
fn shade_sample(pixel: vec2<i32>, s: u32, p: vec3<f32>, light: u32) -> SampleLight {
    let m = textureLoad(material_tex, pixel, s);
    var sum = SampleLight(vec4<f32>(0.0), vec4<f32>(0.0));
    if (unorm8(m.b) & FLAG_LIT) == 0u {
        return sum;
    }
    let n = oct_decode(textureLoad(normal_tex, pixel, s).xy);
    // Only the geometry, the roughness and the layers matter to light_terms: albedo and
    // metalness are the material pass's.
    let surface = Surface(p, n, safe_normalize(-p), vec3<f32>(1.0), 0.0, m.g, 1.0, load_layers(pixel, s, n));
    if light == ALL_DIRECTIONAL {
        // Ambient and environment light need the albedo: the material pass adds them.
        if DIRECTIONAL_LIGHTS {
            for (var i = 0u; i < directional_count(); i++) {
                let terms = light_terms(surface, lights[i]);
                sum.light += terms.light;
                sum.lobes += terms.lobes;
            }
        }
    } else {
        sum = light_terms(surface, lights[light]);
    }
    let most = vec4<f32>(HALF_MAX);
    return SampleLight(min(sum.light, most), min(sum.lobes, most));
}
