// The multisampled G-buffer as the passes after the G-buffer pass read it (group 1).
// A pass binds only the textures its entry points use. Composed with one of
// view_depth_stored.wgsl and view_depth_from_depth.wgsl, which define `load_view_depth`.

@group(1) @binding(0) var albedo_tex: GTexF;
@group(1) @binding(1) var normal_tex: GTexF;
@group(1) @binding(2) var material_tex: GTexF;
@group(1) @binding(4) var stencil_tex: GTexU;
// The depth aspect, where the pass attaches the depth-stencil read-only.
@group(1) @binding(5) var depth_tex: GTexD;

struct GSample {
    albedo: vec3<f32>,
    // Ambient occlusion (albedo's alpha): scales ambient light only.
    occlusion: f32,
    normal: vec3<f32>,
    metallic: f32,
    roughness: f32,
    flags: u32,
    edge_bits: u32,
    // 0 where no geometry was drawn.
    view_depth: f32,
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
    return g;
}
