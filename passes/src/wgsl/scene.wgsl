// The shared GPU scene (gpu_scene/ uploads it; group 0 of every pass that draws it).
// Positions are camera-relative world space: world minus the camera position, computed
// in f64 on the CPU, so scenes far from the origin keep their precision.

struct Camera {
    // Camera-relative world to clip space, for the output's aspect ratio.
    view_proj: mat4x4<f32>,
    inv_view_proj: mat4x4<f32>,
    // Unit view direction: a point's view depth is dot(position, forward).
    forward: vec3<f32>,
    _pad0: f32,
    // Output size in pixels.
    viewport: vec2<f32>,
    _pad1: vec2<f32>,
}

struct MeshData {
    model: mat4x4<f32>,
    normal_matrix: mat3x3<f32>,
    material: u32,
    // The mesh's first index in the scene's index buffer, and the offset its indices add
    // to reach the scene's vertex buffer (geometry.wgsl).
    first_index: u32,
    base_vertex: i32,
}

struct MaterialData {
    base_color: vec4<f32>,
    emission: vec3<f32>,
    // Fragments with base alpha below this are discarded (alpha MASK only).
    alpha_cutoff: f32,
    metallic: f32,
    roughness: f32,
    flags: u32,
    // Scales the normal texture's X and Y; 0 without a normal texture, so the white texel
    // bound in its place leaves the normal as it is.
    normal_scale: f32,
    // glTF occlusionTexture strength (0 without one: the white texel then changes nothing).
    occlusion_strength: f32,
    // Bit `slot` (material.wgsl's binding / 2) set: that texture samples TEXCOORD_1.
    uv_sets: u32,
    _pad0: u32,
    _pad1: u32,
    // KHR_materials_ior and _specular: the dielectric F0, ((ior - 1) / (ior + 1))^2 times
    // specularColorFactor (clamped to 1 after the specular colour texture), and
    // specularFactor.
    specular_f0: vec3<f32>,
    specular: f32,
    // KHR_materials_sheen: sheenColorFactor and sheenRoughnessFactor.
    sheen_color: vec3<f32>,
    sheen_roughness: f32,
    // KHR_materials_clearcoat: clearcoatFactor, clearcoatRoughnessFactor, and the scale
    // of clearcoatNormalTexture's X and Y (0 without one, as normal_scale).
    clearcoat: f32,
    clearcoat_roughness: f32,
    clearcoat_normal_scale: f32,
    _pad2: u32,
    // Per slot, KHR_texture_transform: a texture samples uv_transforms[slot] * (uv, 1).
    uv_transforms: array<mat3x2<f32>, 12>,
}

const LIGHT_DIRECTIONAL: u32 = 0u;
const LIGHT_POINT: u32 = 1u;
const LIGHT_SPOT: u32 = 2u;

struct LightData {
    // Unit volume mesh to camera-relative world (point and spot lights).
    volume: mat4x4<f32>,
    position: vec3<f32>,
    // Distance where the light's windowed falloff reaches zero.
    range: f32,
    // Unit direction the light travels (spot and directional lights).
    direction: vec3<f32>,
    kind: u32,
    // Color times intensity.
    radiance: vec3<f32>,
    // Spot cone falloff: clamp(cos_angle * spot_scale + spot_offset, 0, 1)^2.
    spot_scale: f32,
    spot_offset: f32,
    // A sphere around everything a point or spot light reaches, for culling: centered
    // `bound_offset` along `direction` from `position`, of radius `bound_radius`
    // (negative for a light that reaches nothing).
    bound_offset: f32,
    bound_radius: f32,
    // The light's first view in shadow.wgsl's shadow_views (a directional light's
    // cascades follow it), or NO_SHADOW.
    shadow: u32,
}

struct LightInfo {
    ambient: vec3<f32>,
    // Directional lights come first in `lights`.
    directional_count: u32,
    // `lights` holds at least one entry, so this may be less than its length.
    light_count: u32,
    _pad0: u32,
    _pad1: u32,
    _pad2: u32,
    // Image-based lighting (lighting.wgsl): the prefiltered radiance's scale and its
    // cube map's last mip level (roughness 1).
    environment_intensity: f32,
    environment_max_level: f32,
    // A factor on the tone mapper's exposure: the frame's (FrameInputs::exposure).
    exposure: f32,
    _pad4: f32,
    // The environment's irradiance E(n) = sum of irradiance[i] * polynomial i of n
    // (scene/src/environment.rs), already scaled by its intensity.
    irradiance: array<vec4<f32>, 9>,
}

@group(0) @binding(0) var<uniform> camera: Camera;
@group(0) @binding(1) var<storage, read> meshes: array<MeshData>;
@group(0) @binding(2) var<storage, read> materials: array<MaterialData>;
@group(0) @binding(3) var<storage, read> lights: array<LightData>;
@group(0) @binding(4) var<uniform> light_info: LightInfo;
// Image-based lighting (gpu_scene/environment.rs, lighting.wgsl): the environment's
// radiance prefiltered by roughness in the mip levels of a cube map (level 0 the
// radiance itself, which the background shows), and the split-sum lookup table (n.v
// across, roughness down) of the specular BRDF's scale and bias on F0.
@group(0) @binding(5) var environment_tex: texture_cube<f32>;
@group(0) @binding(6) var environment_sampler: sampler;
@group(0) @binding(7) var split_sum_tex: texture_2d<f32>;

// The frame's light counts: read them through these, never from light_info directly.
// Clamped to the light buffer's length, which keeps every loop over `lights` in bounds,
// and which keeps a loop bound or branch from depending on uniform values alone: lavapipe
// (Mesa 22.3) inlines such uniforms by compiling the shader again at every pipeline bind
// and never frees the old one, which leaked about 1.2 MB a frame in the tiled light pass
// (tests/soak.rs guards it).
fn light_count() -> u32 {
    return min(light_info.light_count, arrayLength(&lights));
}

fn directional_count() -> u32 {
    return min(light_info.directional_count, arrayLength(&lights));
}

fn clip_to_ndc(h: vec4<f32>) -> vec3<f32> {
    return h.xyz / h.w;
}

// The camera-relative position of the point at pixel coordinate `pixel` and clip depth
// `depth` (a depth buffer's value).
fn unproject(pixel: vec2<f32>, depth: f32) -> vec3<f32> {
    let ndc = vec2<f32>(pixel.x / camera.viewport.x * 2.0 - 1.0, 1.0 - pixel.y / camera.viewport.y * 2.0);
    return clip_to_ndc(camera.inv_view_proj * vec4<f32>(ndc, depth, 1.0));
}

// The camera-relative position of the surface seen through pixel coordinate `pixel` at
// view depth `depth`: the ray through the pixel, unprojected at two clip depths that are
// finite for every projection and convention, meets the plane of that view depth.
fn surface_position(pixel: vec2<f32>, depth: f32) -> vec3<f32> {
    let a = unproject(pixel, 0.5);
    let b = unproject(pixel, 0.25);
    let along = dot(b - a, camera.forward);
    let t = (depth - dot(a, camera.forward)) / select(along, 1e-20, abs(along) < 1e-20);
    return a + (b - a) * t;
}
