// The material layers a G-buffer stores where its scene's materials use them
// (common/gbuffer_layers.rs: a target each, which the plan keeps only for a scene with
// the layer's feature), encoded by the passes that write a G-buffer and decoded by every
// pass that lights one, through these functions alone. Composed after common.wgsl.
//
//   specular   rgba8unorm   the dielectric F0 (RGB) as its square root, the specular weight
//   clearcoat  rg8unorm     strength, roughness; rgba16float where the coat bends apart
//                           from its base (feature clearcoat_normal): and its octahedral
//                           normal
//   sheen      rgba8unorm   the colour as its square root, roughness
//
// Colours as square roots: finer steps near black (F0 is 0.04 for most dielectrics, 0.2
// squared, which the unorm byte 51 holds exactly), and one multiply to decode.

fn encode_specular(l: Layers) -> vec4<f32> {
    return vec4<f32>(sqrt(l.specular_f0), l.specular);
}

fn encode_clearcoat(l: Layers) -> vec4<f32> {
    return vec4<f32>(l.clearcoat, l.clearcoat_roughness, oct_encode(l.clearcoat_normal));
}

fn encode_sheen(l: Layers) -> vec4<f32> {
    return vec4<f32>(sqrt(l.sheen_color), l.sheen_roughness);
}

// `layers` with the specular layer of the specular target's `texel`.
fn decode_specular(layers: Layers, texel: vec4<f32>) -> Layers {
    var l = layers;
    l.specular_f0 = texel.rgb * texel.rgb;
    l.specular = texel.a;
    return l;
}

// `layers` with the coat of the clearcoat target's `texel`: its own normal where
// `own_normal` (the rgba16float target), else the base's `normal`, which is the coat's
// wherever the scene has no clearcoat_normal.
fn decode_clearcoat(layers: Layers, texel: vec4<f32>, normal: vec3<f32>, own_normal: bool) -> Layers {
    var l = layers;
    l.clearcoat = texel.r;
    l.clearcoat_roughness = texel.g;
    l.clearcoat_normal = select(normal, oct_decode(texel.ba), own_normal);
    return l;
}

// `layers` with the sheen of the sheen target's `texel`.
fn decode_sheen(layers: Layers, texel: vec4<f32>) -> Layers {
    var l = layers;
    l.sheen_color = texel.rgb * texel.rgb;
    l.sheen_roughness = texel.a;
    return l;
}
