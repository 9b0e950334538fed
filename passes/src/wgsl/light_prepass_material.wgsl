// The light pre-pass's two geometry passes (passes/light_prepass.rs), with forward.wgsl's
// vertex stages and material model: both draw the scene from one module, so both place
// every vertex with the same code and the second pass's depth test finds the first's
// depths exactly. Composed after forward.wgsl.
//
// `fs_thin_gbuffer` writes the thin G-buffer the light passes read: the normal, the
// material target (only its roughness and flags matter to the light, but it has
// gbuffer.wgsl's layout so the edge pass reads it as it reads the G-buffer's) and the view
// depth, as gbuffer.wgsl writes them.
//
// `fs_apply_material` runs per sample (the light buffer differs between the samples of
// an edge pixel) and turns the light the sample received (light_prepass.wgsl's light
// buffer) into its colour with the surface's albedo and metalness, plus the ambient and
// environment light and emission.

// The light buffer (rgba16float, the G-buffer's sample count), group 2.
@group(2) @binding(0) var light_tex: GTexF;

struct ThinGBuffer {
    @location(0) normal: vec4<f32>,
    @location(1) material: vec4<f32>,
    @location(2) view_depth: vec4<f32>,
}

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
    var out: ThinGBuffer;
    out.normal = vec4<f32>(oct_encode(normal_of(a, m, front)), 0.0, 0.0);
    out.material = vec4<f32>(m.metallic, m.roughness, f32(material.flags) / 255.0, 0.0);
    out.view_depth = vec4<f32>(dot(a.position, camera.forward), 0.0, 0.0, 0.0);
    return out;
}

// The light buffer's light on surface `s` (light_prepass.wgsl says what it holds): the
// diffuse light times the surface's diffuse colour, plus the dielectric specular coloured
// like the diffuse light and its Fresnel scaled from F0 = 0.04 to the surface's f0, with
// n.v standing in for each light's v.h (exactly 1 for a dielectric).
fn received(s: Surface, light: vec4<f32>) -> vec3<f32> {
    let f0 = mix(vec3<f32>(0.04), s.albedo, s.metallic);
    let diffuse = (1.0 - f0) * (1.0 - s.metallic) * s.albedo / PI * light.rgb;
    let chroma = light.rgb / max(luminance(light.rgb), 1e-20);
    let schlick = pow(1.0 - clamp(dot(s.normal, s.view), 0.0, 1.0), 5.0);
    let fresnel = (f0 + (1.0 - f0) * schlick) / (0.04 + (1.0 - 0.04) * schlick);
    return diffuse + chroma * light.a * fresnel;
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
        // The light buffer holds the core model's lobes only: no layers.
        let s = Surface(a.position, normal_of(a, m, front), safe_normalize(-a.position), m.base.rgb, m.metallic, m.roughness, m.occlusion, plain_layers());
        let light = textureLoad(light_tex, pixel_of(in.clip), sample);
        color += ambient_light(s) + received(s, light);
    }
    return vec4<f32>(min(color, vec3<f32>(HALF_MAX)), 1.0);
}
