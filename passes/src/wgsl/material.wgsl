// The material model: what a material's factors and texels make of a surface, one source
// for every pass that shades the scene (the G-buffer and forward passes fetch texels from
// a material's bound textures, material_bound.wgsl; the visibility buffer's shading from
// the scene's texture table, material_table.wgsl), so every pipeline renders the same
// material. Composed after common.wgsl and scene.wgsl, before one of those two.
//
// A texture a material lacks reads as white, which multiplies its factor by exactly one.

// Which material features the scene has (variant.rs); the defaults are the
// general shader. Without textures of a kind every material's is white, without emission
// it is zero: the gated code would change nothing.
override TEXTURES: bool = true;
override EMISSIVE_TEXTURES: bool = true;
override METAL_ROUGH_TEXTURES: bool = true;
override NORMAL_TEXTURES: bool = true;
override OCCLUSION_TEXTURES: bool = true;
override EMISSIVE: bool = true;

// A material's parameters at one point of a surface.
struct MaterialSample {
    // Linear RGB and alpha.
    base: vec4<f32>,
    // Emitted radiance.
    emission: vec3<f32>,
    metallic: f32,
    roughness: f32,
    // The tangent-space normal, X and Y scaled by the material's normal_scale; (0, 0, 1)
    // leaves the surface normal as it is.
    tangent_normal: vec3<f32>,
    // Scales ambient light only: 1 + strength * (occlusion texel - 1), as glTF defines it.
    occlusion: f32,
}

// Which of `uv0` and `uv1` (TEXCOORD_0 and TEXCOORD_1, or their changes across the
// screen) the texture of `slot` (0 base color, 1 emissive, 2 metallicRoughness, 3
// normal, 4 occlusion) reads, as the material says.
fn slot_set(m: MaterialData, slot: u32, uv0: vec2<f32>, uv1: vec2<f32>) -> vec2<f32> {
    return select(uv0, uv1, ((m.uv_sets >> slot) & 1u) != 0u);
}

// The KHR_texture_transform of the texture of `slot`.
fn slot_transform(m: MaterialData, slot: u32) -> mat3x2<f32> {
    var transforms = m.uv_transforms;
    return transforms[slot];
}

// The texture coordinates the texture of `slot` samples: TEXCOORD_0 `uv0` or TEXCOORD_1
// `uv1`, as the material says, through its KHR_texture_transform.
fn slot_uv(m: MaterialData, slot: u32, uv0: vec2<f32>, uv1: vec2<f32>) -> vec2<f32> {
    return slot_transform(m, slot) * vec3<f32>(slot_set(m, slot, uv0, uv1), 1.0);
}

// A material's five texels at one point, in slot order (base color, emissive,
// metallicRoughness, normal, occlusion); white where a material has no such texture or
// the scene's variant compiles its sampling out.
struct MaterialTexels {
    base: vec4<f32>,
    emissive: vec4<f32>,
    metal_rough: vec4<f32>,
    normal: vec4<f32>,
    occlusion: vec4<f32>,
}

fn white_texels() -> MaterialTexels {
    let white = vec4<f32>(1.0);
    return MaterialTexels(white, white, white, white, white);
}

// Material `m` with texels `t` and vertex color `color` (COLOR_0, white without one),
// which multiplies the base color as glTF says.
fn material_from_texels(m: MaterialData, color: vec4<f32>, t: MaterialTexels) -> MaterialSample {
    var out = MaterialSample(m.base_color * color * t.base, vec3<f32>(0.0), m.metallic * t.metal_rough.b, m.roughness * t.metal_rough.g, vec3<f32>(0.0, 0.0, 1.0), 1.0);
    if EMISSIVE {
        out.emission = m.emission * t.emissive.rgb;
    }
    if NORMAL_TEXTURES {
        let s = t.normal.xyz * 2.0 - 1.0;
        out.tangent_normal = vec3<f32>(s.xy * m.normal_scale, s.z);
    }
    if OCCLUSION_TEXTURES {
        out.occlusion = 1.0 + m.occlusion_strength * (t.occlusion.r - 1.0);
    }
    return out;
}

// The shading normal: `tangent_normal` (a MaterialSample's) in the frame of the
// interpolated world-space `normal` and `tangent` (xyz, and w the bitangent's sign:
// bitangent = w * normal x tangent, as glTF defines it). Unperturbed where the vertices
// have no tangent. Not unit length.
fn shading_normal(normal: vec3<f32>, tangent: vec4<f32>, tangent_normal: vec3<f32>) -> vec3<f32> {
    if !NORMAL_TEXTURES {
        return normal;
    }
    let n = safe_normalize(normal);
    // Interpolation and non-uniform scale leave the tangent off perpendicular: Gram-Schmidt.
    let t = tangent.xyz - n * dot(n, tangent.xyz);
    if dot(t, t) < 1e-12 {
        return normal;
    }
    let b = cross(n, safe_normalize(t)) * select(-1.0, 1.0, tangent.w >= 0.0);
    return safe_normalize(t) * tangent_normal.x + b * tangent_normal.y + n * tangent_normal.z;
}
