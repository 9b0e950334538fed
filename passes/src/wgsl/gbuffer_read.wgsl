// The multisampled G-buffer as the passes after the G-buffer pass read it (group 1).
// A pass binds only the textures its entry points use. Composed after
// gbuffer_layers.wgsl, and with one of view_depth_stored.wgsl and
// view_depth_from_depth.wgsl, which define `load_view_depth`, and a `load_layers` (the
// material layers the G-buffer holds: common/gbuffer_layers.rs generates it, or
// gbuffer_core_layers.wgsl).

@group(1) @binding(0) var albedo_tex: GTexF;
@group(1) @binding(1) var normal_tex: GTexF;
@group(1) @binding(2) var material_tex: GTexF;
@group(1) @binding(4) var stencil_tex: GTexU;
// The depth aspect, where the pass attaches the depth-stencil read-only.
@group(1) @binding(5) var depth_tex: GTexD;

// Sample `s`'s depth buffer value.
fn sample_depth(pixel: vec2<i32>, s: u32) -> f32 {
    return textureLoad(depth_tex, pixel, s);
}

fn material_flags(pixel: vec2<i32>, s: u32) -> vec2<u32> {
    let m = textureLoad(material_tex, pixel, s);
    return vec2<u32>(unorm8(m.b), unorm8(m.a));
}

fn load_gsample(pixel: vec2<i32>, s: u32) -> GSample {
    let m = textureLoad(material_tex, pixel, s);
    var g: GSample;
    let albedo = textureLoad(albedo_tex, pixel, s);
    g.albedo = albedo.rgb;
    g.occlusion = albedo.a;
    g.normal = oct_decode(textureLoad(normal_tex, pixel, s).xy);
    g.metallic = m.r;
    g.roughness = m.g;
    g.flags = unorm8(m.b);
    g.edge_bits = unorm8(m.a);
    g.view_depth = load_view_depth(pixel, s);
    g.layers = load_layers(pixel, s, g.normal);
    return g;
}

// The surface of the fragment led by sample `s`: a G-buffer's samples of one fragment
// hold what it wrote, so sample `s`'s (visibility_read.wgsl's joins triangles).
fn load_fragment(pixel: vec2<i32>, s: u32, mask: u32) -> GSample {
    return load_gsample(pixel, s);
}

// A G-buffer's samples carry no surface IDs: what one fragment wrote is found by
// comparing values (light_tiled.wgsl's same_fragment).
const SURFACE_IDS: bool = false;

// Which samples hold one fragment is known only from their values: each sample leads its
// own here (four bits per sample, as light_tiled.wgsl's leader_of reads them), and
// light_tiled.wgsl compares values where it needs to.
fn fragment_leaders(pixel: vec2<i32>) -> u32 {
    var leaders = 0u;
    for (var s = 0u; s < SAMPLES; s++) {
        leaders |= s << (4u * s);
    }
    return leaders;
}

// Whether sample `s` shows a surface the light passes shade.
fn sample_lit(pixel: vec2<i32>, s: u32) -> bool {
    return (material_flags(pixel, s).x & FLAG_LIT) != 0u;
}
