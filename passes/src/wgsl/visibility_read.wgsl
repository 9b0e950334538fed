// A visibility buffer as the tiled shading pass reads it: per sample the ID + 1 of the
// triangle it shows and its depth, through `sample_id` and `sample_depth`, and whether a
// pixel's samples all show one triangle, through `one_surface` (visibility_textures.wgsl
// for a raster pass's targets, visibility_samples.wgsl for a compute rasteriser's
// buffer); the triangles from the scene's geometry (group 2,
// geometry.wgsl). Each triangle a pixel shows is rebuilt once, at the mean position of
// the samples it covers (the pixel center when it covers them all, as a G-buffer pass's
// centroid interpolation places it): barycentrics where the ray through that point meets the
// triangle's plane (plane_hit.wgsl), then its attributes and material as the G-buffer pass
// computes them, textures from the scene's texture table (material_table.wgsl, group 3).
// Composed after geometry.wgsl, material.wgsl, material_table.wgsl and plane_hit.wgsl, and with
// view_depth_from_depth.wgsl, which the shading pass's per-pixel surface takes its depth
// from.

// Samples of one triangle are one fragment, exactly (light_tiled.wgsl's same_fragment).
const SURFACE_IDS: bool = true;

// Triangle `id` (+ 1) as seen through pixel coordinate `at`: its attributes and material
// (textures from the scene's texture table, filtered for the pixel's footprint there) as
// the G-buffer pass computes them.
fn rebuild(id: u32, at: vec2<f32>) -> GSample {
    let triangle = id - 1u;
    let mesh = meshes[mesh_of_triangle(triangle)];
    let v0 = pull_vertex(3u * triangle, mesh);
    let v1 = pull_vertex(3u * triangle + 1u, mesh);
    let v2 = pull_vertex(3u * triangle + 2u, mesh);
    let p0 = (mesh.model * vec4<f32>(v0.position, 1.0)).xyz;
    let e1 = (mesh.model * vec4<f32>(v1.position, 1.0)).xyz - p0;
    let e2 = (mesh.model * vec4<f32>(v2.position, 1.0)).xyz - p0;
    let hit = hit_plane(at, p0, e1, e2);
    let b = hit.b;
    // Untextured materials skip the ray differentials (every scene without textures).
    var step = QuadSteps(b, b);
    if material_textured(mesh.material) {
        step = quad_steps(at, b, p0, e1, e2);
    }
    let right = step.right;
    let down = step.down;
    // Counter-clockwise on screen is the front (wgpu's default front face): the geometric
    // normal faces the camera.
    let front = dot(cross(e1, e2), hit.ray) < 0.0;
    let material = materials[mesh.material];
    let color = b.x * v0.color + b.y * v1.color + b.z * v2.color;
    let interpolated = mesh.normal_matrix * (b.x * v0.normal + b.y * v1.normal + b.z * v2.normal);
    let normal = normal_or_face(interpolated, cross(e1, e2));
    // Tangents lie in the surface: they transform with the model matrix (gbuffer.wgsl).
    let tangent_xyz = b.x * v0.tangent.xyz + b.y * v1.tangent.xyz + b.z * v2.tangent.xyz;
    let tangent = vec4<f32>((mesh.model * vec4<f32>(tangent_xyz, 0.0)).xyz, b.x * v0.tangent.w + b.y * v1.tangent.w + b.z * v2.tangent.w);
    let m = sample_material_table(
        mesh.material,
        material,
        color,
        tex_coords(b, v0, v1, v2),
        tex_coords(right, v0, v1, v2),
        tex_coords(down, v0, v1, v2),
    );
    let mapped = shading_normal(normal, tangent, m.tangent_normal);
    var g: GSample;
    g.albedo = m.base.rgb;
    g.occlusion = m.occlusion;
    // Back faces reach here only for double-sided materials: light their other side (the
    // normal texture's perturbation turned around with it).
    g.normal = unit_normal(select(-mapped, mapped, front));
    g.metallic = m.metallic;
    g.roughness = m.roughness;
    g.flags = material.flags;
    g.id = id;
    g.emission = m.emission;
    // The fragment's view depth where it is rebuilt, as a G-buffer stores it: one per
    // triangle and pixel.
    g.view_depth = dot(hit.origin + hit.along * hit.ray, camera.forward);
    return g;
}

fn pixel_ids(pixel: vec2<i32>) -> array<u32, SAMPLES> {
    var ids: array<u32, SAMPLES>;
    for (var s = 0u; s < SAMPLES; s++) {
        ids[s] = sample_id(pixel, s);
    }
    return ids;
}

// A pixel's samples, read once for everything its fragments need: each one's triangle
// (ID + 1, 0 for nothing drawn) and clip depth.
struct PixelSamples {
    ids: array<u32, SAMPLES>,
    depths: array<f32, SAMPLES>,
}

fn read_samples(pixel: vec2<i32>) -> PixelSamples {
    var samples: PixelSamples;
    for (var s = 0u; s < SAMPLES; s++) {
        samples.ids[s] = sample_id(pixel, s);
        samples.depths[s] = sample_depth(pixel, s);
    }
    return samples;
}

// The samples among `ids` showing triangle `id`, a bit each.
fn showing(ids: array<u32, SAMPLES>, id: u32) -> u32 {
    var mask = 0u;
    for (var k = 0u; k < SAMPLES; k++) {
        mask |= u32(ids[k] == id) << k;
    }
    return mask;
}

// The mean position of the samples of `mask` in `pixel`.
fn mean_position(pixel: vec2<i32>, mask: u32) -> vec2<f32> {
    var at = vec2<f32>(0.0);
    var n = 0.0;
    for (var k = 0u; k < SAMPLES; k++) {
        if (mask & (1u << k)) != 0u {
            at += sample_position(pixel, k);
            n += 1.0;
        }
    }
    return at / n;
}

// Where sample `s` of `pixel` is rebuilt: the triangle it shows (ID + 1, 0 for nothing
// drawn) at the mean position of the samples showing it. A pixel whose samples all show
// one triangle takes it at the pixel center (the mean of the standard sample positions,
// exactly) from sample 0's ID, reading no other sample.
struct SampleFragment {
    id: u32,
    at: vec2<f32>,
}

fn sample_fragment(pixel: vec2<i32>, s: u32) -> SampleFragment {
    if one_surface(pixel) {
        return SampleFragment(sample_id(pixel, 0u), vec2<f32>(pixel) + 0.5);
    }
    return fragment_of(pixel, pixel_ids(pixel), s);
}

// sample_fragment from the pixel's IDs, read before.
fn fragment_of(pixel: vec2<i32>, ids: array<u32, SAMPLES>, s: u32) -> SampleFragment {
    // ids[s], without indexing the array by a variable (which may put it in memory).
    var id = 0u;
    for (var k = 0u; k < SAMPLES; k++) {
        id = select(id, ids[k], k == s);
    }
    return SampleFragment(id, mean_position(pixel, showing(ids, id)));
}

// Fragment `f` as a G-buffer sample. Nothing drawn: view depth 0, as a G-buffer's.
fn rebuilt(f: SampleFragment) -> GSample {
    if f.id == 0u {
        return GSample();
    }
    return rebuild(f.id, f.at);
}

// Sample `s` of `pixel` as a G-buffer sample. One call of `rebuild` for either kind of
// pixel: a warp holding both runs it once.
fn load_gsample(pixel: vec2<i32>, s: u32) -> GSample {
    return rebuilt(sample_fragment(pixel, s));
}

// For each sample, the first sample showing the same triangle (itself where no earlier
// one does), four bits per sample as light_tiled.wgsl's leader_of reads them: a pixel's
// fragments from its IDs alone, so each triangle is rebuilt once.
fn fragment_leaders(pixel: vec2<i32>) -> u32 {
    if one_surface(pixel) {
        return 0u;
    }
    return leaders_of(pixel_ids(pixel));
}

// fragment_leaders from the pixel's IDs, read before.
fn leaders_of(ids: array<u32, SAMPLES>) -> u32 {
    var leaders = 0u;
    for (var s = 0u; s < SAMPLES; s++) {
        var leader = s;
        for (var j = 0u; j < s; j++) {
            if ids[j] == ids[s] {
                leader = j;
                break;
            }
        }
        leaders |= leader << (4u * s);
    }
    return leaders;
}

// Whether sample `s` shows a surface the light passes shade: its triangle's material's
// flags, without rebuilding it.
fn sample_lit(pixel: vec2<i32>, s: u32) -> bool {
    let id = sample_id(pixel, s);
    return id != 0u && (materials[meshes[mesh_of_triangle(id - 1u)].material].flags & FLAG_LIT) != 0u;
}
