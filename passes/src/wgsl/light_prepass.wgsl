// The light pre-pass's `shade_sample` for light.wgsl: the light a thin G-buffer sample
// receives, before its material is known, added to the light buffer (passes/
// light_prepass.rs). Composed after surface.wgsl; `light` is a light's index or
// light.wgsl's ALL_DIRECTIONAL. The thin G-buffer has normals, view depth and the
// material target's roughness and flags (its metalness is never read here).
//
// For each light of radiance c (attenuated, times the cosine) brdf.wgsl's shading is
//   diffuse  (1 - f0) (1 - metallic) albedo / pi  *  c (1 - schlick)
//   specular D V (f0 + (1 - f0) schlick)  *  c
// The light buffer keeps, summed over lights:
//   rgb: c (1 - schlick), the diffuse light: exact for any albedo and f0, which factor out;
//   a:   the luminance of a dielectric's specular, D V (0.04 + 0.96 schlick) c.
// The material pass (light_prepass_material.wgsl) colours the specular with the diffuse
// light's chroma and scales its Fresnel to the surface's f0, so it is exact for
// dielectrics under white light and approximate for metals and coloured light: the
// classic light pre-pass trade of one specular channel for a thinner light buffer.

fn light_terms(s: Surface, light: LightData) -> vec4<f32> {
    let i = incident(s.position, light);
    let k = lobe(s, i.l);
    if k.n_l <= 0.0 {
        return vec4<f32>(0.0);
    }
    // As far as its shadow map lets it through (shadow.wgsl, or shadow_none.wgsl where the
    // pass reads no atlas), as lighting.wgsl's direct_light scales it.
    let c = light.radiance * i.attenuation * k.n_l * light_visibility(s, light);
    let dielectric = k.specular * (0.04 + (1.0 - 0.04) * k.schlick);
    return vec4<f32>(c * (1.0 - k.schlick), luminance(c) * dielectric);
}

// The light sample `s` of `pixel`, the surface point `p` (camera-relative), receives.
fn shade_sample(pixel: vec2<i32>, s: u32, p: vec3<f32>, light: u32) -> vec4<f32> {
    let m = textureLoad(material_tex, pixel, s);
    if (unorm8(m.b) & FLAG_LIT) == 0u {
        return vec4<f32>(0.0);
    }
    let n = oct_decode(textureLoad(normal_tex, pixel, s).xy);
    // Only the geometry and roughness matter to light_terms: albedo and metalness are the
    // material pass's.
    let surface = Surface(p, n, safe_normalize(-p), vec3<f32>(1.0), 0.0, m.g, 1.0, plain_layers());
    var sum = vec4<f32>(0.0);
    if light == ALL_DIRECTIONAL {
        // Ambient and environment light need the albedo: the material pass adds them.
        if DIRECTIONAL_LIGHTS {
            for (var i = 0u; i < directional_count(); i++) {
                sum += light_terms(surface, lights[i]);
            }
        }
    } else {
        sum = light_terms(surface, lights[light]);
    }
    return min(sum, vec4<f32>(HALF_MAX));
}
