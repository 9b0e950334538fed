// A material's textures bound one bind group per material (group 1: gpu_scene/materials.rs),
// as the G-buffer and forward passes read them. Composed after material.wgsl.
//
// A material without one of these textures binds a white texel.

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

// Material `m` at texture coordinates `uv0` and `uv1` with vertex color `color`.
// Sampled in uniform control flow: callers discard only after this returns.
fn sample_material(m: MaterialData, uv0: vec2<f32>, uv1: vec2<f32>, color: vec4<f32>) -> MaterialSample {
    var t = white_texels();
    if TEXTURES {
        t.base = textureSample(base_color_tex, base_color_sampler, slot_uv(m, 0u, uv0, uv1));
    }
    if EMISSIVE && EMISSIVE_TEXTURES {
        t.emissive = textureSample(emissive_tex, emissive_sampler, slot_uv(m, 1u, uv0, uv1));
    }
    if METAL_ROUGH_TEXTURES {
        t.metal_rough = textureSample(metal_rough_tex, metal_rough_sampler, slot_uv(m, 2u, uv0, uv1));
    }
    if NORMAL_TEXTURES {
        t.normal = textureSample(normal_tex, normal_sampler, slot_uv(m, 3u, uv0, uv1));
    }
    if OCCLUSION_TEXTURES {
        t.occlusion = textureSample(occlusion_tex, occlusion_sampler, slot_uv(m, 4u, uv0, uv1));
    }
    return material_from_texels(m, color, t);
}
