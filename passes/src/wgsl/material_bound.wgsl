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
// The extensions' textures (material.wgsl's MaterialTexels says which channels count).
@group(1) @binding(10) var specular_tex: texture_2d<f32>;
@group(1) @binding(11) var specular_sampler: sampler;
@group(1) @binding(12) var specular_color_tex: texture_2d<f32>;
@group(1) @binding(13) var specular_color_sampler: sampler;
@group(1) @binding(14) var clearcoat_tex: texture_2d<f32>;
@group(1) @binding(15) var clearcoat_sampler: sampler;
@group(1) @binding(16) var clearcoat_roughness_tex: texture_2d<f32>;
@group(1) @binding(17) var clearcoat_roughness_sampler: sampler;
@group(1) @binding(18) var clearcoat_normal_tex: texture_2d<f32>;
@group(1) @binding(19) var clearcoat_normal_sampler: sampler;
@group(1) @binding(20) var sheen_color_tex: texture_2d<f32>;
@group(1) @binding(21) var sheen_color_sampler: sampler;
@group(1) @binding(22) var sheen_roughness_tex: texture_2d<f32>;
@group(1) @binding(23) var sheen_roughness_sampler: sampler;

// The texture coordinates TEXCOORD_0 and TEXCOORD_1 at a fragment (interpolated where
// it is shaded: the centroid of the covered samples, or a sample) and their changes one
// pixel right (dx) and one pixel down (dy).
struct FragmentUv {
    uv0: vec2<f32>,
    uv1: vec2<f32>,
    dx0: vec2<f32>,
    dy0: vec2<f32>,
    dx1: vec2<f32>,
    dy1: vec2<f32>,
}

// A fragment's texture coordinates `uv0` and `uv1` with the derivatives of `at_center`,
// the same two interpolated at pixel centers (xy TEXCOORD_0, zw TEXCOORD_1), or at the
// samples shaded where shading runs per sample. Taken at pixel centers because the
// centroids of a 2x2 quad lie unevenly spaced where a triangle edge crosses it, which
// skews the differences of centroid coordinates there (and the level of detail with
// them). Call in uniform control flow, on interpolated values only (sample_slot says
// why).
fn fragment_uv(uv0: vec2<f32>, uv1: vec2<f32>, at_center: vec4<f32>) -> FragmentUv {
    let dx = dpdx(at_center);
    let dy = dpdy(at_center);
    return FragmentUv(uv0, uv1, dx.xy, dy.xy, dx.zw, dy.zw);
}

// The texel of `tex` through `s` for the texture of material `m`'s `slot` at `at`.
//
// Explicit gradients, not textureSample: the derivatives of the interpolated coordinates
// themselves, through the linear part of the slot's transform (what implicit derivatives
// of the transformed coordinates are, where helper invocations run the shader fully).
// Mesa's llvmpipe 22.3.6 (Debian 12's lavapipe; 25.0.7 is fixed) runs no storage-buffer
// load for a 2x2 quad's helper invocations, which read zero: a transform from `materials`
// maps their coordinates to (0, 0), and implicit derivatives in every quad that a
// triangle edge crosses pick the 1x1 mip level, a dotted seam of the texture's average
// colour along every edge the rasteriser draws (docs/lavapipe-seams.md).
fn sample_slot(tex: texture_2d<f32>, s: sampler, m: MaterialData, slot: u32, at: FragmentUv) -> vec4<f32> {
    let t = slot_transform(m, slot);
    let linear = mat2x2<f32>(t[0], t[1]);
    let dx = linear * slot_set(m, slot, at.dx0, at.dx1);
    let dy = linear * slot_set(m, slot, at.dy0, at.dy1);
    return textureSampleGrad(tex, s, slot_uv(m, slot, at.uv0, at.uv1), dx, dy);
}

// Material `m` at texture coordinates `at` (fragment_uv's) with vertex color `color`.
// Sampled in uniform control flow: callers discard only after this returns.
fn sample_material(m: MaterialData, at: FragmentUv, color: vec4<f32>) -> MaterialSample {
    var t = white_texels();
    if TEXTURES {
        t.base = sample_slot(base_color_tex, base_color_sampler, m, 0u, at);
    }
    if EMISSIVE && EMISSIVE_TEXTURES {
        t.emissive = sample_slot(emissive_tex, emissive_sampler, m, 1u, at);
    }
    if METAL_ROUGH_TEXTURES {
        t.metal_rough = sample_slot(metal_rough_tex, metal_rough_sampler, m, 2u, at);
    }
    if NORMAL_TEXTURES {
        t.normal = sample_slot(normal_tex, normal_sampler, m, 3u, at);
    }
    if OCCLUSION_TEXTURES {
        t.occlusion = sample_slot(occlusion_tex, occlusion_sampler, m, 4u, at);
    }
    if SPECULAR {
        t.specular = sample_slot(specular_tex, specular_sampler, m, 5u, at);
        t.specular_color = sample_slot(specular_color_tex, specular_color_sampler, m, 6u, at);
    }
    if CLEARCOAT {
        t.clearcoat = sample_slot(clearcoat_tex, clearcoat_sampler, m, 7u, at);
        t.clearcoat_roughness = sample_slot(clearcoat_roughness_tex, clearcoat_roughness_sampler, m, 8u, at);
        t.clearcoat_normal = sample_slot(clearcoat_normal_tex, clearcoat_normal_sampler, m, 9u, at);
    }
    if SHEEN {
        t.sheen_color = sample_slot(sheen_color_tex, sheen_color_sampler, m, 10u, at);
        t.sheen_roughness = sample_slot(sheen_roughness_tex, sheen_roughness_sampler, m, 11u, at);
    }
    return material_from_texels(m, color, t);
}
