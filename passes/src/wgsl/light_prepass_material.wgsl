// The light pre-pass's two geometry passes (passes/light_prepass.rs), with forward.wgsl's
// vertex stages and material model: both draw the scene from one module, so both place
// every vertex with the same code and the second pass's depth test finds the first's
// depths exactly. Composed after forward.wgsl and gbuffer_layers.wgsl, and before the
// generated `ThinGBuffer` and `thin_gbuffer` (the thin G-buffer's targets: the material
// layers among them where the pass writes them), `LOBES` and `load_lobes` (the material
// pass reads the lobes buffer: passes/light_prepass.rs).
//
// `fs_thin_gbuffer` writes the thin G-buffer the light passes read: the normal, the
// material target (only its roughness and flags matter to the light, but it has
// gbuffer.wgsl's layout so the edge pass reads it as it reads the G-buffer's), the view
// depth, as gbuffer.wgsl writes them, and the clear coat and sheen whose lobes the light
// passes sum.
//
// `fs_apply_material` runs per sample (the light buffer differs between the samples of
// an edge pixel) and turns the light the sample received (light_prepass.wgsl's light
// buffer, and its lobes buffer) into its colour with the surface's albedo, metalness and
// layers, plus the ambient and environment light and emission.

// The light buffer (rgba16float, the G-buffer's sample count), group 2.
@group(2) @binding(0) var light_tex: GTexF;

// The shading normal, as forward.wgsl's `shade_surface` and gbuffer.wgsl find it.
fn normal_of(a: Attributes, m: MaterialSample, front: bool) -> vec3<f32> {
    let mapped = shading_normal(a.normal, a.tangent, m.tangent_normal);
    return unit_normal(select(-mapped, mapped, front || !DOUBLE_SIDED));
}

@fragment
fn fs_thin_gbuffer(in: PixelVaryings, @builtin(front_facing) front: bool) -> ThinGBuffer {
    let a = pixel_attributes(in, front);
    let material = materials[a.material];
    let m = sample_material(material, fragment_uv(a.uv, a.uv1, a.uv_center), a.color);
    if MASKED && m.base.a < material.alpha_cutoff {
        discard;
    }
    let normal = vec4<f32>(oct_encode(normal_of(a, m, front)), 0.0, 0.0);
    let flags = vec4<f32>(m.metallic, m.roughness, f32(material.flags) / 255.0, 0.0);
    let view_depth = vec4<f32>(dot(a.position, camera.forward), 0.0, 0.0, 0.0);
    let layers = surface_layers(m, a.normal, a.tangent, front || !DOUBLE_SIDED);
    return thin_gbuffer(normal, flags, view_depth, layers);
}

// The light buffer's light on surface `s` (light_prepass.wgsl says what it holds): the
// diffuse light times the surface's diffuse colour, plus the specular coloured like the
// diffuse light and its Fresnel scaled from the dielectric's (F0 0.04, F90 1) to the
// surface's (its metalness and KHR_materials_specular's F0 and weight: brdf.wgsl's
// reflectance), with n.v standing in for each light's v.h (exactly 1 for the core
// dielectric). With the lobes buffer's `lobes`, the sheen over that (dimming it by the
// mean E the lobes carry) and the clear coat over both (coated: weighed by the coat's
// Fresnel), as brdf.wgsl layers them. The specular weight's own share of the diffuse,
// (1 - F90) times each light's Schlick term, is left out (exact where light arrives
// along the view).
fn received(s: Surface, light: vec4<f32>, lobes: vec4<f32>) -> vec3<f32> {
    let r = reflectance(s);
    let diffuse = (1.0 - r.f0) * (1.0 - s.metallic) * s.albedo / PI * light.rgb;
    let brightness = max(luminance(light.rgb), 1e-20);
    let chroma = light.rgb / brightness;
    let schlick = pow(1.0 - clamp(dot(s.normal, s.view), 0.0, 1.0), 5.0);
    let ratio = fresnel(r, schlick) / (0.04 + (1.0 - 0.04) * schlick);
    var color = diffuse + chroma * light.a * ratio;
    if has_sheen(s) {
        let c = s.layers.sheen_color;
        let taken = lobes.b / brightness;
        color = color * (1.0 - max(c.r, max(c.g, c.b)) * taken) + c * chroma * lobes.g;
    }
    if CLEARCOAT && s.layers.clearcoat > 0.0 {
        color = coated(s, color, chroma * lobes.r);
    }
    return color;
}

@fragment
fn fs_apply_material(
    in: SampleVaryings,
    @builtin(front_facing) front: bool,
    @builtin(sample_index) sample: u32,
) -> @location(0) vec4<f32> {
    let a = sample_attributes(in, front);
    let material = materials[a.material];
    let m = sample_material(material, fragment_uv(a.uv, a.uv1, a.uv_center), a.color);
    if MASKED && m.base.a < material.alpha_cutoff {
        discard;
    }
    var color = m.emission;
    if (material.flags & FLAG_UNLIT) != 0u {
        color += m.base.rgb;
    } else {
        // The specular layer needs nothing of the light passes; the coat and the sheen
        // need their lobes, and without the lobes buffer are left out.
        var layers = surface_layers(m, a.normal, a.tangent, front || !DOUBLE_SIDED);
        if !LOBES {
            let plain = plain_layers();
            layers.clearcoat = plain.clearcoat;
            layers.sheen_color = plain.sheen_color;
        }
        let s = Surface(a.position, normal_of(a, m, front), safe_normalize(-a.position), m.base.rgb, m.metallic, m.roughness, m.occlusion, layers);
        let pixel = pixel_of(in.clip);
        let light = textureLoad(light_tex, pixel, sample);
        // A clear coat dims what the surface emits as it dims the light it reflects.
        color = color * (1.0 - coat_weight(s.layers, s.view)) + ambient_light(s) + received(s, light, load_lobes(pixel, sample));
    }
    return vec4<f32>(min(color, vec3<f32>(HALF_MAX)), 1.0);
}
