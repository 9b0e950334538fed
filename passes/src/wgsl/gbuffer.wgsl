// The G-buffer pass: one draw per mesh (instance index = mesh index), writing
// albedo, octahedral normal, material, linear view depth and the HDR target (emission,
// or the whole color of unlit materials, so that it is added exactly once).
// Composed after common.wgsl, scene.wgsl, material.wgsl, brdf.wgsl (coat_weight) and
// gbuffer_layers.wgsl, and before the generated
// `GBufferOut` and `gbuffer_out`, which keep the channels the pass writes (an unlit-only
// scene's G-buffer has no normal or material) at consecutive locations, and `last_pose`
// (common/pose_offset.rs: gbuffer_last_pose.wgsl where the pass writes a pose offset).
//
// Channels: albedo = base color RGB (textured, times COLOR_0) and ambient occlusion in
// alpha (otherwise unused, so occlusion costs no byte); normal = octahedral shading normal
// (after the normal texture);
// material = metallic and roughness after their texture, flags, edge bits; view depth;
// HDR = emission after its texture (or the whole unlit color); mesh = the mesh index + 1
// in two halves (optional: a temporal filter's motion vectors read it); pose offset = where
// a deformed mesh's point was in its last pose, from where it is, in world space (optional:
// the same motion vectors read it in scenes with skins or morph targets). The lean G-buffer has
// neither view depth (later passes take it from the depth buffer) nor HDR: its emission
// channel holds only the emission, in RGB9E5 (common.wgsl) split over an rg16uint, and the light pass takes an
// unlit surface's color from albedo. Textures change what the channels hold, not how
// many there are. The material layers' targets (specular, clearcoat, sheen), where the
// pass has them, hold gbuffer_layers.wgsl's encodings; a coat the G-buffer holds dims the
// emission under it, as it dims the light (`HOLDS_CLEARCOAT`, generated with the
// outputs).

// Whether the scene has double-sided materials (variant.rs; the default is the
// general shader): without them back faces are culled and the flip changes nothing.
override DOUBLE_SIDED: bool = true;

struct VertexIn {
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) uv: vec2<f32>,
    @location(3) color: vec4<f32>,
    @location(4) tangent: vec4<f32>,
    @location(5) uv1: vec2<f32>,
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
    @location(6) @interpolate(perspective, centroid) color: vec4<f32>,
    // World-space tangent, w the bitangent's sign.
    @location(7) @interpolate(perspective, centroid) tangent: vec4<f32>,
    @location(8) @interpolate(perspective, centroid) uv1: vec2<f32>,
    // uv and uv1 at the pixel center, for their derivatives (material_bound.wgsl's
    // fragment_uv).
    @location(9) @interpolate(perspective, center) uv_center: vec4<f32>,
    // The camera-relative position, for the face normal of a mesh without vertex normals
    // (common.wgsl's normal_or_face): its derivatives lie in the triangle's plane.
    @location(10) @interpolate(perspective, center) position: vec3<f32>,
    // The mesh index, for the optional mesh channel (motion vectors of moving objects).
    @location(11) @interpolate(flat) mesh: u32,
    // The pose offset (see above) at the pixel centre, for the optional pose offset
    // channel, which the fragment stage moves to sample 0 (`pose_offset_at_sample_0`).
    @location(12) @interpolate(perspective, center) pose_offset: vec3<f32>,
}

// Every channel the pass can write; `gbuffer_out` picks those it does.
struct GBuffer {
    albedo: vec4<f32>,
    normal: vec4<f32>,
    material: vec4<f32>,
    view_depth: vec4<f32>,
    hdr: vec4<f32>,
    emission: vec2<u32>,
    mesh: vec2<u32>,
    pose_offset: vec4<f32>,
    specular: vec4<f32>,
    clearcoat: vec4<f32>,
    sheen: vec4<f32>,
}

// `index` is the vertex's in the scene's vertex buffer (draw_meshes' base vertex added).
@vertex
fn vs_main(
    v: VertexIn,
    @builtin(instance_index) mesh_index: u32,
    @builtin(vertex_index) index: u32,
) -> Varyings {
    let mesh = meshes[mesh_index];
    let p = (mesh.model * vec4<f32>(v.position, 1.0)).xyz;
    var out: Varyings;
    out.clip = camera.view_proj * vec4<f32>(p, 1.0);
    out.normal = mesh.normal_matrix * v.normal;
    out.uv = v.uv;
    out.uv1 = v.uv1;
    out.uv_center = vec4<f32>(v.uv, v.uv1);
    out.color = v.color;
    // Tangents lie in the surface: they transform with the model matrix, not the normal
    // matrix.
    out.tangent = vec4<f32>((mesh.model * vec4<f32>(v.tangent.xyz, 0.0)).xyz, v.tangent.w);
    out.view_depth = dot(p, camera.forward);
    out.material = mesh.material;
    out.at_centroid = out.clip.xy;
    out.at_center = out.clip.xy;
    out.position = p;
    out.mesh = mesh_index;
    out.pose_offset = (mesh.model * vec4<f32>(last_pose(index, v.position) - v.position, 0.0)).xyz;
    return out;
}

// The pose offset at sample 0's position within the pixel, where the motion vectors take
// its point from the depth, from `at_centre`'s: linear over the pixel, so the derivatives
// (taken before any discard) move it there. A pixel whose centre misses the triangle
// extrapolates, as its centre-interpolated value already does.
fn pose_offset_at_sample_0(at_centre: vec3<f32>) -> vec3<f32> {
    let d = SAMPLE_POSITIONS[0] - vec2<f32>(0.5);
    return at_centre + dpdxFine(at_centre) * d.x + dpdyFine(at_centre) * d.y;
}

fn surface(in: Varyings, m: MaterialSample, front: bool, coverage: u32, pose_offset: vec3<f32>) -> GBuffer {
    let material = materials[in.material];
    let normal = normal_or_face(in.normal, winding_normal(in.position, front));
    // Back faces reach here only for double-sided materials: light their other side (the
    // normal texture's perturbation turned around with it).
    let mapped = shading_normal(normal, in.tangent, m.tangent_normal);
    let n = unit_normal(select(-mapped, mapped, front || !DOUBLE_SIDED));
    var edge = 0u;
    if any(in.at_centroid != in.at_center) {
        edge |= EDGE_CENTROID;
    }
    if coverage != (1u << SAMPLES) - 1u {
        edge |= EDGE_COVERAGE;
    }
    let unlit = (material.flags & FLAG_UNLIT) != 0u;
    let layers = surface_layers(m, normal, in.tangent, front || !DOUBLE_SIDED);
    var emission = m.emission;
    if HOLDS_CLEARCOAT && !unlit {
        emission *= 1.0 - coat_weight(layers, safe_normalize(-in.position));
    }
    var out: GBuffer;
    out.albedo = vec4<f32>(m.base.rgb, m.occlusion);
    out.normal = vec4<f32>(oct_encode(n), 0.0, 0.0);
    out.material = vec4<f32>(m.metallic, m.roughness, f32(material.flags), f32(edge)) / vec4<f32>(1.0, 1.0, 255.0, 255.0);
    out.view_depth = vec4<f32>(in.view_depth, 0.0, 0.0, 0.0);
    let emitted = select(emission, m.base.rgb + emission, unlit);
    out.hdr = vec4<f32>(min(emitted, vec3<f32>(HALF_MAX)), 1.0);
    let packed = pack_rgb9e5(emission);
    out.emission = vec2<u32>(packed & 0xffffu, packed >> 16u);
    let mesh = in.mesh + 1u;
    out.mesh = vec2<u32>(mesh & 0xffffu, mesh >> 16u);
    out.pose_offset = vec4<f32>(pose_offset, 0.0);
    out.specular = encode_specular(layers);
    out.clearcoat = encode_clearcoat(layers);
    out.sheen = encode_sheen(layers);
    return out;
}

@fragment
fn fs_opaque(
    in: Varyings,
    @builtin(front_facing) front: bool,
    @builtin(sample_mask) coverage: u32,
) -> GBufferOut {
    let m = sample_material(materials[in.material], fragment_uv(in.uv, in.uv1, in.uv_center), in.color);
    let pose_offset = pose_offset_at_sample_0(in.pose_offset);
    return gbuffer_out(surface(in, m, front, coverage, pose_offset));
}

// Alpha MASK: coverage is decided per pixel by the base color's alpha.
@fragment
fn fs_masked(
    in: Varyings,
    @builtin(front_facing) front: bool,
    @builtin(sample_mask) coverage: u32,
) -> GBufferOut {
    let m = sample_material(materials[in.material], fragment_uv(in.uv, in.uv1, in.uv_center), in.color);
    let pose_offset = pose_offset_at_sample_0(in.pose_offset);
    if m.base.a < materials[in.material].alpha_cutoff {
        discard;
    }
    return gbuffer_out(surface(in, m, front, coverage, pose_offset));
}
