// A material's textures (group 1, one bind group per material: gpu_scene/materials.rs) and
// what the G-buffer and forward passes read from them, so every pipeline renders the same
// material model. Composed after common.wgsl and scene.wgsl.
//
// A material without one of these textures binds a white texel, which multiplies its
// factor by exactly one.

@group(1) @binding(0) var base_color_tex: texture_2d<f32>;
@group(1) @binding(1) var base_color_sampler: sampler;
@group(1) @binding(2) var emissive_tex: texture_2d<f32>;
@group(1) @binding(3) var emissive_sampler: sampler;
// Linear data, glTF's packing: blue is metalness, green roughness.
@group(1) @binding(4) var metal_rough_tex: texture_2d<f32>;
@group(1) @binding(5) var metal_rough_sampler: sampler;
// Linear tangent-space normals, glTF's convention: +X along the tangent, +Y up the image.
@group(1) @binding(6) var normal_tex: texture_2d<f32>;
@group(1) @binding(7) var normal_sampler: sampler;
// Linear data: red is ambient occlusion.
@group(1) @binding(8) var occlusion_tex: texture_2d<f32>;
@group(1) @binding(9) var occlusion_sampler: sampler;

// Which material features the scene has (analysis/variant.rs); the defaults are the
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

// The texture coordinates the texture of `slot` (its binding / 2) samples: TEXCOORD_0
// `uv0` or TEXCOORD_1 `uv1`, as the material says, through its KHR_texture_transform.
fn slot_uv(m: MaterialData, slot: u32, uv0: vec2<f32>, uv1: vec2<f32>) -> vec2<f32> {
    let uv = select(uv0, uv1, ((m.uv_sets >> slot) & 1u) != 0u);
    var transforms = m.uv_transforms;
    return transforms[slot] * vec3<f32>(uv, 1.0);
}

// Material `m` at texture coordinates `uv0` and `uv1` with vertex color `color` (COLOR_0,
// white without one), which multiplies the base color as glTF says. Sampled in uniform
// control flow: callers discard only after this returns.
fn sample_material(m: MaterialData, uv0: vec2<f32>, uv1: vec2<f32>, color: vec4<f32>) -> MaterialSample {
    var out = MaterialSample(m.base_color * color, vec3<f32>(0.0), m.metallic, m.roughness, vec3<f32>(0.0, 0.0, 1.0), 1.0);
    if TEXTURES {
        out.base *= textureSample(base_color_tex, base_color_sampler, slot_uv(m, 0u, uv0, uv1));
    }
    if EMISSIVE {
        out.emission = m.emission;
        if EMISSIVE_TEXTURES {
            out.emission *= textureSample(emissive_tex, emissive_sampler, slot_uv(m, 1u, uv0, uv1)).rgb;
        }
    }
    if METAL_ROUGH_TEXTURES {
        let packed = textureSample(metal_rough_tex, metal_rough_sampler, slot_uv(m, 2u, uv0, uv1));
        out.metallic *= packed.b;
        out.roughness *= packed.g;
    }
    if NORMAL_TEXTURES {
        let s = textureSample(normal_tex, normal_sampler, slot_uv(m, 3u, uv0, uv1)).xyz * 2.0 - 1.0;
        out.tangent_normal = vec3<f32>(s.xy * m.normal_scale, s.z);
    }
    if OCCLUSION_TEXTURES {
        let texel = textureSample(occlusion_tex, occlusion_sampler, slot_uv(m, 4u, uv0, uv1)).r;
        out.occlusion = 1.0 + m.occlusion_strength * (texel - 1.0);
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
