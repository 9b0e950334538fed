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
// from, and edge_detect.wgsl, whose depth_step smooth_join tests.

// Samples of one triangle are one fragment, exactly (light_tiled.wgsl's same_fragment).
const SURFACE_IDS: bool = true;

// Whether samples of triangles joining into one smooth surface are one fragment too
// (smooth_join; light_tiled's `shading: surfaces`).
override SMOOTH_SURFACES: bool = false;
// The cosine under which smooth_join's faces bend too far to be lit as one: 8 degrees,
// stricter than the compare detector's NORMAL_THRESHOLD (0.95, 18 degrees), because the
// joined fragment is lit with its triangles' mean normal (at 0.95 and 0.98 builtin:lights'
// small spheres kept under 99% of their pixels within 1/255 of their triangles lit apart).
const SMOOTH_NORMAL: f32 = 0.99;

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
    g.layers = surface_layers(m, normal, tangent, front);
    let position = hit.origin + hit.along * hit.ray;
    // A clear coat dims what the surface emits as it dims the light it reflects.
    g.emission = m.emission * (1.0 - coat_weight(g.layers, safe_normalize(-position)));
    // The fragment's view depth where it is rebuilt, as a G-buffer stores it: one per
    // triangle and pixel.
    g.view_depth = dot(position, camera.forward);
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
    let id = id_at(ids, s);
    return SampleFragment(id, mean_position(pixel, showing(ids, id)));
}

// ids[s], without indexing the array by a variable (which may put it in memory).
fn id_at(ids: array<u32, SAMPLES>, s: u32) -> u32 {
    var id = 0u;
    for (var k = 0u; k < SAMPLES; k++) {
        id = select(id, ids[k], k == s);
    }
    return id;
}

// The surface of `pixel`'s fragment led by sample `s`, covering the samples of `mask`
// (light_tiled.wgsl's source_mask). Without SMOOTH_SURFACES, or where the pixel shows one
// triangle, it is sample `s`'s triangle rebuilt (load_gsample); else joined_gsample.
fn load_fragment(pixel: vec2<i32>, s: u32, mask: u32) -> GSample {
    if !SMOOTH_SURFACES || one_surface(pixel) {
        return load_gsample(pixel, s);
    }
    return joined_gsample(pixel, pixel_ids(pixel), s, mask);
}

// load_fragment from the pixel's IDs, read before. Where smooth_join has joined other
// triangles into the fragment, each is rebuilt at the mean position of its own samples
// there, as it would be alone, and the surfaces are averaged, weighted by the samples each
// covers (the normal renormalised; flags and ID the leader's): the one lighting then
// sees what the samples showed (vertex colours and textures that vary across the
// triangles included), and loses only the lighting's own curvature over the pixel, as a
// pixel shaded once anywhere does.
fn joined_gsample(pixel: vec2<i32>, ids: array<u32, SAMPLES>, s: u32, mask: u32) -> GSample {
    let lead = id_at(ids, s);
    var led = GSample();
    var sum = GSample();
    var done = 0u;
    // One rebuild site, in the loop: a shader inlines each, and this one is large.
    for (var k = 0u; k < SAMPLES; k++) {
        if ((mask & ~done) & (1u << k)) != 0u {
            let id = id_at(ids, k);
            let covered = showing(ids, id) & mask;
            done |= covered;
            let g = rebuilt(SampleFragment(id, mean_position(pixel, covered)));
            if id == lead {
                led = g;
            }
            sum = weighted(sum, g, f32(countOneBits(covered)));
        }
    }
    if (showing(ids, lead) & mask) == mask {
        return led;
    }
    let n = f32(countOneBits(mask));
    var mean = led;
    mean.albedo = sum.albedo / n;
    mean.occlusion = sum.occlusion / n;
    mean.normal = unit_normal(sum.normal);
    mean.metallic = sum.metallic / n;
    mean.roughness = sum.roughness / n;
    mean.view_depth = sum.view_depth / n;
    mean.emission = sum.emission / n;
    mean.layers = mean_layers(sum.layers, n);
    return mean;
}

// `sum` plus `w` times the blendable channels of `g` (joined_gsample's mean).
fn weighted(sum: GSample, g: GSample, w: f32) -> GSample {
    var out = sum;
    out.albedo += w * g.albedo;
    out.occlusion += w * g.occlusion;
    out.normal += w * g.normal;
    out.metallic += w * g.metallic;
    out.roughness += w * g.roughness;
    out.view_depth += w * g.view_depth;
    out.emission += w * g.emission;
    out.layers = weighted_layers(sum.layers, g.layers, w);
    return out;
}

// `sum` plus `w` times the layers the scene has (weighted's part).
fn weighted_layers(sum: Layers, l: Layers, w: f32) -> Layers {
    var out = sum;
    if SPECULAR {
        out.specular_f0 += w * l.specular_f0;
        out.specular += w * l.specular;
    }
    if CLEARCOAT {
        out.clearcoat += w * l.clearcoat;
        out.clearcoat_roughness += w * l.clearcoat_roughness;
        out.clearcoat_normal += w * l.clearcoat_normal;
    }
    if SHEEN {
        out.sheen_color += w * l.sheen_color;
        out.sheen_roughness += w * l.sheen_roughness;
    }
    return out;
}

// The mean of `n` samples' layers whose weighted sum is `sum` (joined_gsample's mean).
fn mean_layers(sum: Layers, n: f32) -> Layers {
    var mean = plain_layers();
    if SPECULAR {
        mean.specular_f0 = sum.specular_f0 / n;
        mean.specular = sum.specular / n;
    }
    if CLEARCOAT {
        mean.clearcoat = sum.clearcoat / n;
        mean.clearcoat_roughness = sum.clearcoat_roughness / n;
        mean.clearcoat_normal = unit_normal(sum.clearcoat_normal);
    }
    if SHEEN {
        mean.sheen_color = sum.sheen_color / n;
        mean.sheen_roughness = sum.sheen_roughness / n;
    }
    return mean;
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

// For each sample, the first sample of the same fragment (itself where no earlier one
// is), four bits per sample as light_tiled.wgsl's leader_of reads them: a pixel's
// fragments from its IDs and depths alone, so each is rebuilt once. Samples of one
// triangle are one fragment; with SMOOTH_SURFACES, so are samples of triangles that
// join into one smooth surface (smooth_join).
fn fragment_leaders(pixel: vec2<i32>) -> u32 {
    if one_surface(pixel) {
        return 0u;
    }
    return leaders_of(pixel, read_samples(pixel));
}

// fragment_leaders from the pixel's samples, read before. A sample joins the fragment of
// the first earlier sample showing its triangle, or failing that of the first earlier
// sample whose triangle joins its own smoothly: a pixel of a dense mesh shows triangles
// that touch only through a third, and the fragment grows along the surface.
fn leaders_of(pixel: vec2<i32>, samples: PixelSamples) -> u32 {
    // Each sample's view depth, for smooth_join, computed once.
    var depths: array<f32, SAMPLES>;
    if SMOOTH_SURFACES {
        for (var s = 0u; s < SAMPLES; s++) {
            depths[s] = dot(unproject(sample_position(pixel, s), samples.depths[s]), camera.forward);
        }
    }
    var leaders = 0u;
    for (var s = 0u; s < SAMPLES; s++) {
        var leader = s;
        for (var j = 0u; j < s; j++) {
            let lead = (leaders >> (4u * j)) & 15u;
            if samples.ids[j] == samples.ids[s] {
                leader = lead;
                break;
            }
            if SMOOTH_SURFACES && smooth_join(samples.ids[j], samples.ids[s], depths[j], depths[s]) {
                leader = lead;
                break;
            }
        }
        leaders |= leader << (4u * s);
    }
    return leaders;
}

// Whether triangles `id_a` and `id_b` (IDs + 1, different ones), seen at view depths
// `depth_a` and `depth_b` by two samples of a pixel, are one smooth surface, so that one
// lighting serves both (light_tiled's `shading: surfaces`; joined_gsample says how):
// triangles of one mesh (one material) sharing a vertex whose normal is given (a zero
// normal asks for the face normal: such triangles are facets, each its own fragment), at
// view depths without the compare detector's depth step between them (edge_detect.wgsl's
// depth_step, 1% by default: a fan's far side seen past its shared centre is not joined),
// and whose faces bend by less than SMOOTH_NORMAL (a thin box's two sides lit once with
// their normals averaged would not light as each side does). Their interpolated normals meet at the shared
// vertex, and a pixel of a dense mesh is then no edge for its triangles alone. Cheapest
// test first: this runs at every pixel showing more than one triangle.
fn smooth_join(id_a: u32, id_b: u32, depth_a: f32, depth_b: f32) -> bool {
    if id_a == 0u || id_b == 0u {
        return false;
    }
    if depth_step(depth_a, depth_b) {
        return false;
    }
    let mesh_index = mesh_of_triangle(id_a - 1u);
    if mesh_of_triangle(id_b - 1u) != mesh_index {
        return false;
    }
    let base = meshes[mesh_index].base_vertex;
    let first_a = 3u * (id_a - 1u);
    let first_b = 3u * (id_b - 1u);
    var shared_normal = false;
    for (var i = 0u; i < 3u; i++) {
        let vertex = index_words[first_a + i];
        for (var k = 0u; k < 3u; k++) {
            if index_words[first_b + k] == vertex && given_normal(u32(i32(vertex) + base)) {
                shared_normal = true;
            }
        }
    }
    if !shared_normal {
        return false;
    }
    let face_a = face_normal(first_a, meshes[mesh_index]);
    let face_b = face_normal(first_b, meshes[mesh_index]);
    return dot(face_a, face_b) >= SMOOTH_NORMAL * length(face_a) * length(face_b);
}

// The direction of the face (unnormalised, object space) of the triangle of `mesh` whose
// indices start at `first`.
fn face_normal(first: u32, mesh: MeshData) -> vec3<f32> {
    let p0 = pull_position(first, mesh);
    return cross(pull_position(first + 1u, mesh) - p0, pull_position(first + 2u, mesh) - p0);
}

// Whether vertex `v` of the scene's vertex buffer has a normal (not zero: geometry.wgsl).
fn given_normal(v: u32) -> bool {
    let w = vertex_words(v);
    let bits = vec3<u32>(vertex_word(w, 3u), vertex_word(w, 4u), vertex_word(w, 5u));
    // Either sign of zero.
    return any((bits & vec3<u32>(0x7fffffffu)) != vec3<u32>(0u));
}

// Whether sample `s` shows a surface the light passes shade: its triangle's material's
// flags, without rebuilding it.
fn sample_lit(pixel: vec2<i32>, s: u32) -> bool {
    let id = sample_id(pixel, s);
    return id != 0u && (materials[meshes[mesh_of_triangle(id - 1u)].material].flags & FLAG_LIT) != 0u;
}
