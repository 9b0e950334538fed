// The G-buffer resolve of the "wrong way" baseline (seed 000, figure 2.8.3): every
// G-buffer target averaged into one value per pixel before lighting, as an MSAA resolve
// would, so the light passes see surfaces that exist nowhere in the scene.
// Composed after common.wgsl, scene.wgsl and gbuffer_read.wgsl (the multisampled inputs).


struct Resolved {
    @location(0) albedo: vec4<f32>,
    @location(1) normal: vec4<f32>,
    @location(2) material: vec4<f32>,
    @location(3) view_depth: vec4<f32>,
    // The averaged view depth as depth, so the light passes' depth tests agree with it.
    @builtin(frag_depth) depth: f32,
}

// Albedo, occlusion, metallic, roughness and view depth are plain averages over all samples, empty
// ones (no geometry: black albedo, depth 0) included, as a box resolve computes them.
// Two things cannot be averaged at all, and get the most charitable treatment instead:
// normals are decoded, summed over the samples with geometry and renormalized (seed 000's
// "custom resolve", still wrong), and the material flags are ORed, so a pixel any lit
// surface touches is lit.
@fragment
fn fs_resolve_gbuffer(@builtin(position) position: vec4<f32>) -> Resolved {
    let pixel = pixel_of(position);
    var albedo = vec3<f32>(0.0);
    var occlusion = 0.0;
    var normal = vec3<f32>(0.0);
    var metal_rough = vec2<f32>(0.0);
    var view_depth = 0.0;
    var flags = 0u;
    for (var s = 0u; s < SAMPLES; s++) {
        let g = load_gsample(pixel, s);
        albedo += g.albedo;
        occlusion += g.occlusion;
        metal_rough += vec2<f32>(g.metallic, g.roughness);
        view_depth += g.view_depth;
        flags |= g.flags;
        if g.view_depth > 0.0 {
            normal += g.normal;
        }
    }
    let n = f32(SAMPLES);
    view_depth /= n;
    var out: Resolved;
    out.albedo = vec4<f32>(albedo / n, occlusion / n);
    out.normal = vec4<f32>(oct_encode(safe_normalize(normal)), 0.0, 0.0);
    out.material = vec4<f32>(metal_rough / n, f32(flags) / 255.0, 0.0);
    out.view_depth = vec4<f32>(view_depth, 0.0, 0.0, 0.0);
    out.depth = FAR_DEPTH;
    if view_depth > 0.0 {
        let p = surface_position(vec2<f32>(pixel) + 0.5, view_depth);
        let clip = camera.view_proj * vec4<f32>(p, 1.0);
        // An averaged depth nearer than the near plane still counts as geometry.
        out.depth = clamp(clip.z / max(clip.w, 1e-20), 0.0, 1.0);
    }
    return out;
}
