// Every material's textures from one compute pass, without binding arrays (WebGPU has
// none): the scene's texture table (group 3, gpu_scene/texture_table.rs and
// scene/src/texture_table.rs). Its images are layers of two 2D array textures with full mip
// chains, sRGB ones (base color, emissive) in `color_layers`, linear ones in
// `data_layers`; per material and slot one word says where its texture is and how the
// glTF sampler samples it. A compute shader has no implicit derivatives, so the caller
// gives each point's texture coordinates one pixel right and one down (ray differentials)
// and the texels are read with textureSampleGrad, as a fragment shader's textureSample
// would read them. Composed after material.wgsl.

// Per material (scene order), per slot (material.wgsl's slot_uv order) a word:
// bits 0-15 the layer (NO_LAYER: no texture, white), bit 16 set for color_layers, bits
// 17-18 and 19-20 the U and V wrap modes (WRAP_*), bit 21 magnification and bit 22
// minification linear (else nearest), bits 23-24 the mipmap filter (MIP_*).
@group(3) @binding(0) var<storage, read> material_slots: array<array<u32, TEXTURE_SLOTS>>;
@group(3) @binding(1) var color_layers: texture_2d_array<f32>;
@group(3) @binding(2) var data_layers: texture_2d_array<f32>;
// Address mode x texel filter x mipmap filter (binding 3 + 4 * clamp + 2 * linear texels +
// linear mips): a slot whose glTF sampler repeats on both axes samples through a
// repeating one, every other through a clamping one, after wrap_axis.
@group(3) @binding(3) var repeat_nearest_mip_nearest: sampler;
@group(3) @binding(4) var repeat_nearest_mip_linear: sampler;
@group(3) @binding(5) var repeat_linear_mip_nearest: sampler;
@group(3) @binding(6) var repeat_linear_mip_linear: sampler;
@group(3) @binding(7) var clamp_nearest_mip_nearest: sampler;
@group(3) @binding(8) var clamp_nearest_mip_linear: sampler;
@group(3) @binding(9) var clamp_linear_mip_nearest: sampler;
@group(3) @binding(10) var clamp_linear_mip_linear: sampler;

const NO_LAYER: u32 = 0xffffu;
const WRAP_REPEAT: u32 = 0u;
const WRAP_MIRRORED: u32 = 1u;
const MIP_NONE: u32 = 0u;
const MIP_LINEAR: u32 = 2u;

// A point's texture coordinates, TEXCOORD_0 and TEXCOORD_1.
struct TexCoords {
    uv0: vec2<f32>,
    uv1: vec2<f32>,
}

// One texture's coordinates at a point and their change one pixel right (dx) and one
// pixel down (dy).
struct UvGrad {
    uv: vec2<f32>,
    dx: vec2<f32>,
    dy: vec2<f32>,
}

fn slot_grad(m: MaterialData, slot: u32, at: TexCoords, right: TexCoords, down: TexCoords) -> UvGrad {
    let uv = slot_uv(m, slot, at.uv0, at.uv1);
    return UvGrad(uv, slot_uv(m, slot, right.uv0, right.uv1) - uv, slot_uv(m, slot, down.uv0, down.uv1) - uv);
}

// Coordinate `u` wrapped by `mode` for a clamping sampler (a slot that does not repeat on
// both axes): MIRRORED_REPEAT folded into [0, 1], which is exact (a mirror's filter
// footprint at the fold reads the edge texels as clamping does), CLAMP_TO_EDGE as it is,
// and REPEAT (beside another mode on the other axis) by its fraction, which filters the
// seam against the edge texel instead of the opposite edge's: the table's one
// approximation of a glTF sampler.
fn wrap_axis(u: f32, mode: u32) -> f32 {
    switch mode {
        case WRAP_REPEAT: {
            return fract(u);
        }
        case WRAP_MIRRORED: {
            return 1.0 - abs(fract(u * 0.5) * 2.0 - 1.0);
        }
        default: {
            return u;
        }
    }
}

fn sample_layers(s: sampler, color: bool, uv: vec2<f32>, layer: u32, dx: vec2<f32>, dy: vec2<f32>) -> vec4<f32> {
    if color {
        return textureSampleGrad(color_layers, s, uv, layer, dx, dy);
    }
    return textureSampleGrad(data_layers, s, uv, layer, dx, dy);
}

// The texel of material `m`'s texture in `slot`, whose word is `word`, at a point whose
// texture coordinates are `point`, and `right` and `down` one pixel over; white without
// one (before any coordinates are computed).
fn table_texel(word: u32, m: MaterialData, slot: u32, point: TexCoords, right: TexCoords, down: TexCoords) -> vec4<f32> {
    let layer = word & NO_LAYER;
    if layer == NO_LAYER {
        return vec4<f32>(1.0);
    }
    let at = slot_grad(m, slot, point, right, down);
    let color = ((word >> 16u) & 1u) != 0u;
    let size = vec2<f32>(select(textureDimensions(data_layers), textureDimensions(color_layers), color));
    // The level of detail a sampler computes (isotropic): at or below 0 it magnifies, and
    // filters as the magnification filter says, above it as the minification filter.
    let tx = at.dx * size;
    let ty = at.dy * size;
    let lod = 0.5 * log2(max(dot(tx, tx), dot(ty, ty)));
    let linear = ((word >> select(22u, 21u, lod <= 0.0)) & 1u) != 0u;
    let mip = (word >> 23u) & 3u;
    var dx = at.dx;
    var dy = at.dy;
    if mip == MIP_NONE {
        // No mipmaps: level 0 only, as a sampler clamped to it reads.
        dx = vec2<f32>(0.0);
        dy = vec2<f32>(0.0);
    }
    let wrap = vec2<u32>((word >> 17u) & 3u, (word >> 19u) & 3u);
    let repeat = all(wrap == vec2<u32>(WRAP_REPEAT));
    var uv = at.uv;
    if !repeat {
        uv = vec2<f32>(wrap_axis(uv.x, wrap.x), wrap_axis(uv.y, wrap.y));
    }
    switch u32(!repeat) * 4u + u32(linear) * 2u + u32(mip == MIP_LINEAR) {
        case 0u: {
            return sample_layers(repeat_nearest_mip_nearest, color, uv, layer, dx, dy);
        }
        case 1u: {
            return sample_layers(repeat_nearest_mip_linear, color, uv, layer, dx, dy);
        }
        case 2u: {
            return sample_layers(repeat_linear_mip_nearest, color, uv, layer, dx, dy);
        }
        case 3u: {
            return sample_layers(repeat_linear_mip_linear, color, uv, layer, dx, dy);
        }
        case 4u: {
            return sample_layers(clamp_nearest_mip_nearest, color, uv, layer, dx, dy);
        }
        case 5u: {
            return sample_layers(clamp_nearest_mip_linear, color, uv, layer, dx, dy);
        }
        case 6u: {
            return sample_layers(clamp_linear_mip_nearest, color, uv, layer, dx, dy);
        }
        default: {
            return sample_layers(clamp_linear_mip_linear, color, uv, layer, dx, dy);
        }
    }
}

// Whether material `index` has a texture in the table: without one its texels are all
// white, and the point needs no derivatives.
fn material_textured(index: u32) -> bool {
    var slots = material_slots[index];
    var textured = false;
    for (var slot = 0u; slot < TEXTURE_SLOTS; slot++) {
        textured = textured || (slots[slot] & NO_LAYER) != NO_LAYER;
    }
    return textured;
}

// Material `index` (`m`, its MaterialData) with vertex color `color` at a point whose
// texture coordinates are `at`, and `right` and `down` one pixel right and down: what
// material_bound.wgsl's sample_material gives a fragment there.
fn sample_material_table(index: u32, m: MaterialData, color: vec4<f32>, at: TexCoords, right: TexCoords, down: TexCoords) -> MaterialSample {
    let slots = material_slots[index];
    var t = white_texels();
    if TEXTURES {
        t.base = table_texel(slots[0], m, 0u, at, right, down);
    }
    if EMISSIVE && EMISSIVE_TEXTURES {
        t.emissive = table_texel(slots[1], m, 1u, at, right, down);
    }
    if METAL_ROUGH_TEXTURES {
        t.metal_rough = table_texel(slots[2], m, 2u, at, right, down);
    }
    if NORMAL_TEXTURES {
        t.normal = table_texel(slots[3], m, 3u, at, right, down);
    }
    if OCCLUSION_TEXTURES {
        t.occlusion = table_texel(slots[4], m, 4u, at, right, down);
    }
    if SPECULAR {
        t.specular = table_texel(slots[5], m, 5u, at, right, down);
        t.specular_color = table_texel(slots[6], m, 6u, at, right, down);
    }
    if CLEARCOAT {
        t.clearcoat = table_texel(slots[7], m, 7u, at, right, down);
        t.clearcoat_roughness = table_texel(slots[8], m, 8u, at, right, down);
        t.clearcoat_normal = table_texel(slots[9], m, 9u, at, right, down);
    }
    if SHEEN {
        t.sheen_color = table_texel(slots[10], m, 10u, at, right, down);
        t.sheen_roughness = table_texel(slots[11], m, 11u, at, right, down);
    }
    return material_from_texels(m, color, t);
}
