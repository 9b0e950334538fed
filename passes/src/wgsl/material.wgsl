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
    // The extensions' layers; the clearcoat normal in tangent space as tangent_normal
    // (surface_layers turns it into the world's).
    layers: Layers,
}

// How many texture slots a material has (gpu_scene/materials.rs's TEXTURE_SLOTS).
const TEXTURE_SLOTS: u32 = 12u;

// Which of `uv0` and `uv1` (TEXCOORD_0 and TEXCOORD_1, or their changes across the
// screen) the texture of `slot` (0 base color, 1 emissive, 2 metallicRoughness, 3
// normal, 4 occlusion, 5 specular, 6 specular colour, 7 clearcoat, 8 clearcoat roughness,
// 9 clearcoat normal, 10 sheen colour, 11 sheen roughness) reads, as the material says.
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

// A material's texels at one point, in slot order; white where a material has no such
// texture or the scene's variant compiles its sampling out.
struct MaterialTexels {
    base: vec4<f32>,
    emissive: vec4<f32>,
    metal_rough: vec4<f32>,
    normal: vec4<f32>,
    occlusion: vec4<f32>,
    // KHR_materials_specular: alpha the specular, RGB the specular colour.
    specular: vec4<f32>,
    specular_color: vec4<f32>,
    // KHR_materials_clearcoat: red the coat, green its roughness, and its normals.
    clearcoat: vec4<f32>,
    clearcoat_roughness: vec4<f32>,
    clearcoat_normal: vec4<f32>,
    // KHR_materials_sheen: RGB its colour, alpha its roughness.
    sheen_color: vec4<f32>,
    sheen_roughness: vec4<f32>,
}

fn white_texels() -> MaterialTexels {
    let white = vec4<f32>(1.0);
    return MaterialTexels(white, white, white, white, white, white, white, white, white, white, white, white);
}

// Material `m` with texels `t` and vertex color `color` (COLOR_0, white without one),
// which multiplies the base color as glTF says.
fn material_from_texels(m: MaterialData, color: vec4<f32>, t: MaterialTexels) -> MaterialSample {
    var out = MaterialSample(m.base_color * color * t.base, vec3<f32>(0.0), m.metallic * t.metal_rough.b, m.roughness * t.metal_rough.g, vec3<f32>(0.0, 0.0, 1.0), 1.0, plain_layers());
    if EMISSIVE {
        out.emission = m.emission * t.emissive.rgb;
    }
    if NORMAL_TEXTURES {
        out.tangent_normal = scaled_normal(t.normal, m.normal_scale);
    }
    if OCCLUSION_TEXTURES {
        out.occlusion = 1.0 + m.occlusion_strength * (t.occlusion.r - 1.0);
    }
    if SPECULAR {
        out.layers.specular_f0 = min(m.specular_f0 * t.specular_color.rgb, vec3<f32>(1.0));
        out.layers.specular = m.specular * t.specular.a;
    }
    if CLEARCOAT {
        out.layers.clearcoat = m.clearcoat * t.clearcoat.r;
        out.layers.clearcoat_roughness = m.clearcoat_roughness * t.clearcoat_roughness.g;
        out.layers.clearcoat_normal = scaled_normal(t.clearcoat_normal, m.clearcoat_normal_scale);
    }
    if SHEEN {
        out.layers.sheen_color = m.sheen_color * t.sheen_color.rgb;
        out.layers.sheen_roughness = m.sheen_roughness * t.sheen_roughness.a;
    }
    return out;
}

// A normal texel as a tangent-space normal, X and Y scaled by `scale` (0 without a
// texture: the white texel then leaves the normal as it is).
fn scaled_normal(texel: vec4<f32>, scale: f32) -> vec3<f32> {
    let s = texel.xyz * 2.0 - 1.0;
    return vec3<f32>(s.xy * scale, s.z);
}

// The shading normal: `tangent_normal` (a MaterialSample's) in the frame of the
// interpolated world-space `normal` and `tangent` (xyz, and w the bitangent's sign:
// bitangent = w * normal x tangent, as glTF defines it). Unperturbed where the vertices
// have no tangent. Not unit length.
fn shading_normal(normal: vec3<f32>, tangent: vec4<f32>, tangent_normal: vec3<f32>) -> vec3<f32> {
    if !NORMAL_TEXTURES {
        return normal;
    }
    return in_tangent_frame(normal, tangent, tangent_normal);
}

fn in_tangent_frame(normal: vec3<f32>, tangent: vec4<f32>, tangent_normal: vec3<f32>) -> vec3<f32> {
    let n = safe_normalize(normal);
    // Interpolation and non-uniform scale leave the tangent off perpendicular: Gram-Schmidt.
    let t = tangent.xyz - n * dot(n, tangent.xyz);
    if dot(t, t) < 1e-12 {
        return normal;
    }
    let b = cross(n, safe_normalize(t)) * select(-1.0, 1.0, tangent.w >= 0.0);
    return safe_normalize(t) * tangent_normal.x + b * tangent_normal.y + n * tangent_normal.z;
}

// `m`'s layers at a surface whose interpolated world-space normal and tangent are `normal`
// and `tangent`, seen from the `front`: the clear coat's normal in the world. The coat
// follows the mesh's normal, perturbed by its own normal texture only (glTF: not by the
// base's), and turns with the base's for a back face.
fn surface_layers(m: MaterialSample, normal: vec3<f32>, tangent: vec4<f32>, front: bool) -> Layers {
    var layers = m.layers;
    if CLEARCOAT {
        let n = in_tangent_frame(normal, tangent, m.layers.clearcoat_normal);
        layers.clearcoat_normal = unit_normal(select(-n, n, front));
    }
    return layers;
}
