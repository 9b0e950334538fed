// The forward pass of the baselines: the scene drawn straight into the multisampled HDR
// target, every light evaluated per fragment with brdf.wgsl's `shade_light` (the code the
// deferred light passes run), so forward and deferred images agree. Emission and unlit
// colors are what gbuffer.wgsl writes into the HDR target; lit surfaces add the ambient
// term and every light, as light.wgsl's draws add them.
// Composed after common.wgsl, scene.wgsl, material.wgsl (the material model gbuffer.wgsl
// reads too), brdf.wgsl and lighting.wgsl.

// Alpha MASK materials: discard below the cutoff (one pipeline per material state).
override MASKED: bool = false;
// Whether the scene has double-sided materials, as in gbuffer.wgsl (variant.rs);
// the material gates are material.wgsl's, the light kinds brdf.wgsl's. The defaults are
// the general shader.
override DOUBLE_SIDED: bool = true;

struct VertexIn {
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) uv: vec2<f32>,
    @location(3) color: vec4<f32>,
    @location(4) tangent: vec4<f32>,
    @location(5) uv1: vec2<f32>,
}

// What shading needs, however it was interpolated.
struct Attributes {
    // Camera-relative world position.
    position: vec3<f32>,
    normal: vec3<f32>,
    uv: vec2<f32>,
    uv1: vec2<f32>,
    // uv and uv1 where their derivatives are taken (material_bound.wgsl's fragment_uv):
    // at the pixel center when shading at the centroid, else where uv and uv1 are.
    uv_center: vec4<f32>,
    color: vec4<f32>,
    // World-space tangent, w the bitangent's sign.
    tangent: vec4<f32>,
    material: u32,
}

// `shading: pixel`: once per pixel, at the centroid of the covered samples as the
// G-buffer pass interpolates (the pixel center may lie outside a partly covering triangle).
struct PixelVaryings {
    @builtin(position) clip: vec4<f32>,
    @location(0) @interpolate(perspective, centroid) position: vec3<f32>,
    @location(1) @interpolate(perspective, centroid) normal: vec3<f32>,
    @location(2) @interpolate(perspective, centroid) uv: vec2<f32>,
    @location(3) @interpolate(flat) material: u32,
    @location(4) @interpolate(perspective, centroid) color: vec4<f32>,
    @location(5) @interpolate(perspective, centroid) tangent: vec4<f32>,
    @location(6) @interpolate(perspective, centroid) uv1: vec2<f32>,
    @location(7) @interpolate(perspective, center) uv_center: vec4<f32>,
    // The position again at the pixel center, for the face normal of a mesh without vertex
    // normals: derivatives of centroid values are not those of the triangle's plane on
    // every device (lavapipe shaded a sphere's faces in noise from them).
    @location(8) @interpolate(perspective, center) position_center: vec3<f32>,
}

// `shading: sample`: `sample` interpolation runs the fragment shader once per covered
// sample, with attributes at that sample's position (supersampling).
struct SampleVaryings {
    @builtin(position) clip: vec4<f32>,
    @location(0) @interpolate(perspective, sample) position: vec3<f32>,
    @location(1) @interpolate(perspective, sample) normal: vec3<f32>,
    @location(2) @interpolate(perspective, sample) uv: vec2<f32>,
    @location(3) @interpolate(flat) material: u32,
    @location(4) @interpolate(perspective, sample) color: vec4<f32>,
    @location(5) @interpolate(perspective, sample) tangent: vec4<f32>,
    @location(6) @interpolate(perspective, sample) uv1: vec2<f32>,
}

fn transform(v: VertexIn, mesh_index: u32) -> Attributes {
    let mesh = meshes[mesh_index];
    let p = (mesh.model * vec4<f32>(v.position, 1.0)).xyz;
    // Tangents lie in the surface: they transform with the model matrix.
    let t = vec4<f32>((mesh.model * vec4<f32>(v.tangent.xyz, 0.0)).xyz, v.tangent.w);
    return Attributes(p, mesh.normal_matrix * v.normal, v.uv, v.uv1, vec4<f32>(v.uv, v.uv1), v.color, t, mesh.material);
}

@vertex
fn vs_pixel(v: VertexIn, @builtin(instance_index) mesh_index: u32) -> PixelVaryings {
    let a = transform(v, mesh_index);
    return PixelVaryings(camera.view_proj * vec4<f32>(a.position, 1.0), a.position, a.normal, a.uv, a.material, a.color, a.tangent, a.uv1, a.uv_center, a.position);
}

@vertex
fn vs_sample(v: VertexIn, @builtin(instance_index) mesh_index: u32) -> SampleVaryings {
    let a = transform(v, mesh_index);
    return SampleVaryings(camera.view_proj * vec4<f32>(a.position, 1.0), a.position, a.normal, a.uv, a.material, a.color, a.tangent, a.uv1);
}

// The surface's colour (emission plus light, or base colour plus emission if unlit) and
// its base alpha: what transparent.wgsl blends, and what `shade` writes opaque.
fn shade_surface(a: Attributes, front: bool) -> vec4<f32> {
    let f = fragment_of(a, front);
    var color = f.m.emission;
    if f.unlit {
        color += f.m.base.rgb;
    } else {
        // A clear coat dims what the surface emits as it dims the light it reflects.
        color = color * (1.0 - coat_weight(f.s.layers, f.s.view)) + every_light(f.s);
    }
    return vec4<f32>(min(color, vec3<f32>(HALF_MAX)), f.m.base.a);
}

// A fragment's material, sampled, and (unless the material is unlit) the surface the
// lights reach. Alpha-masked fragments below the cutoff are discarded here.
struct Fragment {
    m: MaterialSample,
    unlit: bool,
    s: Surface,
}

fn fragment_of(a: Attributes, front: bool) -> Fragment {
    let material = materials[a.material];
    let m = sample_material(material, fragment_uv(a.uv, a.uv1, a.uv_center), a.color);
    if MASKED && m.base.a < material.alpha_cutoff {
        discard;
    }
    var f: Fragment;
    f.m = m;
    f.unlit = (material.flags & FLAG_UNLIT) != 0u;
    if !f.unlit {
        // Back faces reach here only for double-sided materials: light their other side (the
        // normal texture's perturbation turned around with it).
        let mapped = shading_normal(a.normal, a.tangent, m.tangent_normal);
        let n = unit_normal(select(-mapped, mapped, front || !DOUBLE_SIDED));
        let layers = surface_layers(m, a.normal, a.tangent, front || !DOUBLE_SIDED);
        f.s = Surface(a.position, n, safe_normalize(-a.position), m.base.rgb, m.metallic, m.roughness, m.occlusion, layers);
    }
    return f;
}

// `front`: whether the triangle faces the camera, for a face normal (common.wgsl's
// normal_or_face).
fn pixel_attributes(in: PixelVaryings, front: bool) -> Attributes {
    let normal = normal_or_face(in.normal, winding_normal(in.position_center, front));
    return Attributes(in.position, normal, in.uv, in.uv1, in.uv_center, in.color, in.tangent, in.material);
}

// Per sample, derivatives come from the shaded samples' own coordinates: every
// invocation of a quad runs at the same sample of its pixel, one pixel apart.
fn sample_attributes(in: SampleVaryings, front: bool) -> Attributes {
    let normal = normal_or_face(in.normal, winding_normal(in.position, front));
    return Attributes(in.position, normal, in.uv, in.uv1, vec4<f32>(in.uv, in.uv1), in.color, in.tangent, in.material);
}

fn shade(a: Attributes, front: bool) -> vec4<f32> {
    return vec4<f32>(shade_surface(a, front).rgb, 1.0);
}

@fragment
fn fs_pixel(in: PixelVaryings, @builtin(front_facing) front: bool) -> @location(0) vec4<f32> {
    return shade(pixel_attributes(in, front), front);
}

@fragment
fn fs_sample(in: SampleVaryings, @builtin(front_facing) front: bool) -> @location(0) vec4<f32> {
    return shade(sample_attributes(in, front), front);
}
