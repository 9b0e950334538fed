// The G-buffer pass: one draw per mesh (instance index = mesh index), writing
// albedo, octahedral normal, material, linear view depth and the HDR target (emission,
// or the whole color of unlit materials, so that it is added exactly once).
// Composed after common.wgsl and scene.wgsl, and before the generated `GBufferOut` and
// `gbuffer_out`, which keep the channels the pass writes (an unlit-only scene's G-buffer
// has no normal or material) at consecutive locations.

@group(1) @binding(0) var base_color_tex: texture_2d<f32>;
@group(1) @binding(1) var base_color_sampler: sampler;

// Which material features the scene has (analysis/variant.rs); the defaults are the
// general shader. Without textures every material's is white, without double-sided
// materials back faces are culled, without emission it is zero: the gated code would
// change nothing.
override TEXTURES: bool = true;
override DOUBLE_SIDED: bool = true;
override EMISSIVE: bool = true;

struct VertexIn {
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) uv: vec2<f32>,
}

// Attributes are interpolated at the centroid of the covered samples: at a partially
// covered pixel the pixel center may lie outside the triangle, and extrapolated depths
// and normals there would be wrong for the samples the triangle does cover.
struct Varyings {
    @builtin(position) clip: vec4<f32>,
    @location(0) @interpolate(perspective, centroid) normal: vec3<f32>,
    @location(1) @interpolate(perspective, centroid) uv: vec2<f32>,
    @location(2) @interpolate(perspective, centroid) view_depth: f32,
    @location(3) @interpolate(flat) material: u32,
    // The same value at the centroid and at the pixel center: they differ only where the
    // triangle covers part of the pixel (the centroid edge detector of seed 000).
    @location(4) @interpolate(perspective, centroid) at_centroid: vec2<f32>,
    @location(5) @interpolate(perspective, center) at_center: vec2<f32>,
}

// Every channel the pass can write; `gbuffer_out` picks those it does.
struct GBuffer {
    albedo: vec4<f32>,
    normal: vec4<f32>,
    material: vec4<f32>,
    view_depth: vec4<f32>,
    hdr: vec4<f32>,
}

@vertex
fn vs_main(v: VertexIn, @builtin(instance_index) mesh_index: u32) -> Varyings {
    let mesh = meshes[mesh_index];
    let p = (mesh.model * vec4<f32>(v.position, 1.0)).xyz;
    var out: Varyings;
    out.clip = camera.view_proj * vec4<f32>(p, 1.0);
    out.normal = mesh.normal_matrix * v.normal;
    out.uv = v.uv;
    out.view_depth = dot(p, camera.forward);
    out.material = mesh.material;
    out.at_centroid = out.clip.xy;
    out.at_center = out.clip.xy;
    return out;
}

fn base_color(in: Varyings) -> vec4<f32> {
    var base = materials[in.material].base_color;
    if TEXTURES {
        base *= textureSample(base_color_tex, base_color_sampler, in.uv);
    }
    return base;
}

fn surface(in: Varyings, base: vec4<f32>, front: bool, coverage: u32) -> GBuffer {
    let material = materials[in.material];
    // Back faces reach here only for double-sided materials: light their other side.
    let n = unit_normal(select(-in.normal, in.normal, front || !DOUBLE_SIDED));
    var edge = 0u;
    if any(in.at_centroid != in.at_center) {
        edge |= EDGE_CENTROID;
    }
    if coverage != (1u << SAMPLES) - 1u {
        edge |= EDGE_COVERAGE;
    }
    let unlit = (material.flags & FLAG_UNLIT) != 0u;
    var out: GBuffer;
    out.albedo = vec4<f32>(base.rgb, 1.0);
    out.normal = vec4<f32>(oct_encode(n), 0.0, 0.0);
    out.material = vec4<f32>(material.metallic, material.roughness, f32(material.flags), f32(edge)) / vec4<f32>(1.0, 1.0, 255.0, 255.0);
    out.view_depth = vec4<f32>(in.view_depth, 0.0, 0.0, 0.0);
    var emission = vec3<f32>(0.0);
    if EMISSIVE {
        emission = material.emission;
    }
    let emitted = select(emission, base.rgb + emission, unlit);
    out.hdr = vec4<f32>(min(emitted, vec3<f32>(HALF_MAX)), 1.0);
    return out;
}

@fragment
fn fs_opaque(
    in: Varyings,
    @builtin(front_facing) front: bool,
    @builtin(sample_mask) coverage: u32,
) -> GBufferOut {
    return gbuffer_out(surface(in, base_color(in), front, coverage));
}

// Alpha MASK: coverage is decided per pixel by the base color's alpha.
@fragment
fn fs_masked(
    in: Varyings,
    @builtin(front_facing) front: bool,
    @builtin(sample_mask) coverage: u32,
) -> GBufferOut {
    let base = base_color(in);
    if base.a < materials[in.material].alpha_cutoff {
        discard;
    }
    return gbuffer_out(surface(in, base, front, coverage));
}
