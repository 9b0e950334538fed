// The particle pass (seed 001): camera-facing billboards from a storage buffer, one
// instance each, six vertices per instance, with a procedural soft texture (opacity
// falling off as (1 - r^2)^2 from the centre), tested against the scene's depth in the
// fragment shader with soft particles (the seed's zFade), lit by the scene's ambient
// radiance (blended) or emitting their colour (additive). Composed after common.wgsl
// and scene.wgsl; then a generated block binds the scene depth at group 1 binding 0 and
// defines `fn scene_view_depth(pixel: vec2<i32>) -> f32` (passes/particles.rs).

struct Particle {
    // Camera-relative centre.
    position: vec3<f32>,
    // Diameter.
    size: f32,
    color: vec3<f32>,
    alpha: f32,
}

@group(2) @binding(0) var<storage, read> particles: array<Particle>;

// How many of `particles` are drawn: the blended ones first, then the emissive ones
// (gpu_scene/particles.rs).
struct ParticleCounts {
    blended: u32,
    total: u32,
}

@group(2) @binding(1) var<uniform> particle_counts: ParticleCounts;

// The camera's right and up axes in camera-relative world space, from the inverse
// projection: two points at one clip depth lie at one view depth, so their difference is
// perpendicular to the view direction, for every projection. A billboard spans them.
struct BillboardAxes {
    right: vec3<f32>,
    up: vec3<f32>,
}

fn billboard_axes() -> BillboardAxes {
    let centre = camera.viewport * 0.5;
    let origin = unproject(centre, 0.5);
    return BillboardAxes(
        safe_normalize(unproject(centre + vec2<f32>(1.0, 0.0), 0.5) - origin),
        safe_normalize(unproject(centre - vec2<f32>(0.0, 1.0), 0.5) - origin),
    );
}

// zFade = saturate(SOFTNESS * (scene depth - particle depth)): a particle fades out over
// the last 1 / SOFTNESS units before the surface behind it, and is gone at and behind it.
override SOFTNESS: f32 = 4.0;
// Extra multiply-adds per fragment, to measure time against shader cost (seed 001's
// Table 23-2): the result cannot be folded away, and changes no pixel.
override PAD: u32 = 0u;

struct Billboard {
    @builtin(position) clip: vec4<f32>,
    // -1..1 across the disc.
    @location(0) corner: vec2<f32>,
    @location(1) @interpolate(flat) color: vec3<f32>,
    @location(2) @interpolate(flat) alpha: f32,
    @location(3) @interpolate(flat) view_depth: f32,
}

@vertex
fn vs_particle(@builtin(vertex_index) vertex: u32, @builtin(instance_index) instance: u32) -> Billboard {
    var corners = array<vec2<f32>, 6>(
        vec2<f32>(-1.0, -1.0), vec2<f32>(1.0, -1.0), vec2<f32>(1.0, 1.0),
        vec2<f32>(-1.0, -1.0), vec2<f32>(1.0, 1.0), vec2<f32>(-1.0, 1.0),
    );
    let corner = corners[vertex % 6u];
    let p = particles[instance];
    let axes = billboard_axes();
    let world = p.position + (corner.x * axes.right + corner.y * axes.up) * (0.5 * p.size);
    return Billboard(
        camera.view_proj * vec4<f32>(world, 1.0),
        corner,
        p.color,
        p.alpha,
        dot(p.position, camera.forward),
    );
}

// The opacity of a particle of opacity `alpha` and view depth `view_depth` at `corner`
// (-1..1 across its disc), in front of the scene at view depth `scene_depth`: the
// particle's, the soft texture's and the soft-particle fade. The compute raster
// (particles_raster.wgsl) takes it too.
fn particle_opacity(corner: vec2<f32>, alpha: f32, view_depth: f32, scene_depth: f32) -> f32 {
    let r2 = dot(corner, corner);
    let falloff = max(1.0 - r2, 0.0);
    var shape = falloff * falloff;
    var padded = shape;
    for (var i = 0u; i < PAD; i++) {
        padded = fma(padded, 0.999, 0.001);
    }
    // `padded` stays within 0..1, so this adds 0; the compiler cannot know it.
    shape += min(padded, 0.0);
    let fade = saturate(SOFTNESS * (scene_depth - view_depth));
    return alpha * shape * fade;
}

// The fragment's opacity.
fn particle_alpha(in: Billboard) -> f32 {
    return particle_opacity(in.corner, in.alpha, in.view_depth, scene_view_depth(pixel_of(in.clip)));
}

// A blended particle's colour (smoke): albedo lit by the ambient radiance.
fn lit_albedo(color: vec3<f32>) -> vec3<f32> {
    return min(color * light_info.ambient, vec3<f32>(HALF_MAX));
}

// An emissive particle's light (fire): its radiance times its opacity `a`.
fn emitted_light(color: vec3<f32>, a: f32) -> vec3<f32> {
    return min(color * a, vec3<f32>(HALF_MAX));
}

// Blended, with its opacity for the pipeline's over-blending. No `discard` where the
// opacity is 0: blending 0 leaves the target exactly as it was, and a shader without
// discard lets the hardware run the mixed-resolution stencil test before it.
fn blended(in: Billboard) -> vec4<f32> {
    return vec4<f32>(lit_albedo(in.color), particle_alpha(in));
}

// Emissive, for additive blending.
fn additive(in: Billboard) -> vec4<f32> {
    let a = particle_alpha(in);
    return vec4<f32>(emitted_light(in.color, a), a);
}

@fragment
fn fs_blended(in: Billboard) -> @location(0) vec4<f32> {
    return blended(in);
}

@fragment
fn fs_additive(in: Billboard) -> @location(0) vec4<f32> {
    return additive(in);
}

// Off screen the additive particles have their own target, the second attachment.
@fragment
fn fs_additive_apart(in: Billboard) -> @location(1) vec4<f32> {
    return additive(in);
}
