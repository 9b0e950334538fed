// The tiled lighting pass (Lauritzen, "Deferred Rendering for Current and Future
// Rendering Pipelines", SIGGRAPH 2010): cs_light_tiled, one compute workgroup per TILE x
// TILE pixels, one invocation per pixel, classifies, culls, shades and resolves in one
// dispatch.
//
// 1. Classify: each invocation reads its pixel's samples and finds whether they hold
//    different surfaces (edge_detect.wgsl, as the fragment path's edge pass does). An
//    edge pixel's samples other than sample 0 are appended to a workgroup list: every
//    one, or with ADAPTIVE each other fragment once (seed 002's unique fragments).
// 2. Cull: the tile's depth bounds come from the points it shades; point and spot
//    lights are tested against the tile's four side planes and those bounds, in batches
//    of THREADS lights (one per invocation), so any number of lights fits.
// 3. Shade: each invocation lights its pixel's sample 0 (at the pixel center when not an
//    edge) and the edge-list entries from its own index on, THREADS apart: a pixel's
//    extra samples are shaded by other invocations, packed into the first warps, rather
//    than one after another by its own.
// 4. Resolve: each sample's light plus what it emits (emission, unlit colour,
//    background), averaged (box, or resolve.wgsl's tone-mapped weights), stored in the 1x
//    output.
//
// A visibility buffer shaded at more than one sample per pixel finds its edge pixels from
// IDs alone: cs_light_tiled lists them instead (EDGES_LISTED) and light_edges_listed.wgsl
// lights them in a dispatch of their own.
//
// Composed after common.wgsl, scene.wgsl, brdf.wgsl, lighting.wgsl, surface.wgsl and
// edge_detect.wgsl, then a generated block defining TILE (the tile's side in pixels),
// EDGE_CAPACITY (the tile's edge-list entries: every sample of every pixel but one, or 1
// where edge pixels are listed) and OutTex (the output's storage texture type), and
// holding the G-buffer's layout: `load_gsample`, `load_fragment`, `fragment_leaders` and
// `sample_lit`
// (gbuffer_read.wgsl, or visibility_read.wgsl with geometry.wgsl), `load_view_depth`
// (view_depth_stored.wgsl, or view_depth_from_depth.wgsl for the lean G-buffer and the
// visibility buffer) and `emitted` (emitted_hdr.wgsl, emitted_rgb9e5.wgsl or
// emitted_surface.wgsl), where edge pixels are lit (edges_in_tiles.wgsl or
// light_edges_listed.wgsl), and common/ao.rs's `with_screen_ao`.

@group(1) @binding(7) var out_tex: OutTex;

// How edge pixels are found: 0 `compare`, 1 EDGE_BIT in the material (`centroid`,
// `coverage`), 2 every pixel (`all`), 3 none, 4 samples of different triangles (a
// visibility buffer's).
override DETECTOR: u32 = 0u;
// Edge pixels shade each fragment once, weighted by the samples it covers, instead of
// every sample.
override ADAPTIVE: bool = false;
// Cull lights per tile; false lists every light in every tile (the reference culling
// must match).
override CULL: bool = true;
// What the pass writes: 0 the lit, resolved HDR; 1 edge pixels (red, blue elsewhere,
// black without geometry); 2 lights per tile as a heat map; 3 fragments per pixel
// (green 2, blue 3, red 4 or more, dark grey 1, black without geometry); 4 the most
// important shadowed light's visibility term (grey, black without geometry).
override VIEW: u32 = 0u;
// 0: box resolve. 1: each sample weighted by 1 / (1 + EXPOSURE * luminance).
override RESOLVE: u32 = 0u;
override EXPOSURE: f32 = 1.0;
// The lights-per-tile view: blue for 1 light, red for HEAT_MAX or more.
override HEAT_MAX: f32 = 64.0;

const THREADS: u32 = TILE * TILE;
const VIEW_SHADED: u32 = 0u;
const VIEW_EDGES: u32 = 1u;
const VIEW_TILE_LIGHTS: u32 = 2u;
const VIEW_FRAGMENTS: u32 = 3u;
const VIEW_SHADOWS: u32 = 4u;
const VIEW_CASCADES: u32 = 5u;

// The tile's depth bounds as order-preserving keys (depth_key): the largest key of the
// negated depth is the nearest, the largest key of the depth the farthest. 0 (below
// every key) until a lit sample is seen.
var<workgroup> nearest_key: atomic<u32>;
var<workgroup> farthest_key: atomic<u32>;
// The tile's edge-list entries, or where edge pixels are listed, its edge pixels.
var<workgroup> edge_count: atomic<u32>;
var<workgroup> batch_light_count: atomic<u32>;
// The lights of this batch that reach the tile.
var<workgroup> batch_lights: array<u32, THREADS>;
// Edge-list entries: the pixel's index in the tile << 12 | the samples its fragment
// covers (a mask) << 4 | its first sample.
var<workgroup> edge_samples: array<u32, EDGE_CAPACITY>;
// Their light, red, green and blue of entry i at 3i, 3i + 1 and 3i + 2 (an array of
// vec3 would pad each to 16 bytes).
var<workgroup> edge_light: array<f32, 3u * EDGE_CAPACITY>;
// The tile's side planes (inward normal, offset), camera-relative.
var<workgroup> tile_planes: array<vec4<f32>, 4>;

// Order-preserving: depth_key(a) < depth_key(b) exactly when a < b, negative depths too.
fn depth_key(d: f32) -> u32 {
    let bits = bitcast<u32>(d);
    return select(bits | 0x80000000u, ~bits, (bits & 0x80000000u) != 0u);
}

fn key_depth(key: u32) -> f32 {
    return bitcast<f32>(select(~key, key & 0x7fffffffu, (key & 0x80000000u) != 0u));
}

fn include_depth(p: vec3<f32>) {
    let depth = dot(p, camera.forward);
    include_depths(depth, depth);
}

// Widens the tile's depth bounds to view depths `nearest` to `farthest`.
fn include_depths(nearest: f32, farthest: f32) {
    atomicMax(&nearest_key, depth_key(-nearest));
    atomicMax(&farthest_key, depth_key(farthest));
}

// The plane through the camera rays of pixel coordinates `a` and `b`, facing `inside`.
// Each ray is unprojected at two clip depths that are finite for every projection and
// convention (scene.wgsl's surface_position does the same).
fn side_plane(a: vec2<f32>, b: vec2<f32>, inside: vec3<f32>) -> vec4<f32> {
    let pa = unproject(a, 0.5);
    let along = unproject(a, 0.25) - pa;
    var n = safe_normalize(cross(unproject(b, 0.5) - pa, along));
    n = select(n, -n, dot(n, inside - pa) < 0.0);
    return vec4<f32>(n, -dot(n, pa));
}

// The side planes of the rectangle of pixels from `corner`, `size` wide and high: one per
// invocation of the first four, corners clockwise from the top left.
fn set_side_plane(corner: vec2<f32>, size: vec2<f32>, local: u32) {
    if local < 4u {
        let corners = array<vec2<f32>, 5>(vec2<f32>(0.0, 0.0), vec2<f32>(1.0, 0.0), vec2<f32>(1.0, 1.0), vec2<f32>(0.0, 1.0), vec2<f32>(0.0, 0.0));
        tile_planes[local] = side_plane(corner + corners[local] * size, corner + corners[local + 1u] * size, unproject(corner + 0.5 * size, 0.5));
    }
}

// Whether point or spot light `light` may reach a point of the tile between view depths
// `nearest` and `farthest`: its bounding sphere (scene.wgsl's LightData) against the
// side planes and the depth bounds, with a relative margin for rounding.
fn reaches_tile(light: LightData, nearest: f32, farthest: f32) -> bool {
    if light.bound_radius < 0.0 {
        return false;
    }
    let center = light.position + light.direction * light.bound_offset;
    let depth = dot(center, camera.forward);
    let radius = light.bound_radius * 1.001 + 1e-6 * abs(depth);
    var inside = depth + radius >= nearest && depth - radius <= farthest;
    for (var i = 0u; i < 4u; i++) {
        inside = inside && dot(tile_planes[i].xyz, center) + tile_planes[i].w >= -radius;
    }
    return inside;
}

// Whether two samples hold what one fragment wrote: the G-buffer pass shades once per
// pixel and triangle, so the samples a fragment covers hold identical values (seed
// 002's unique fragments). Samples of two triangles differ in something, if only in
// their interpolated view depth; a visibility buffer's samples name their triangle.
// Without a stored view depth each sample has its own
// depth along the fragment's slope: then depths within the compare detector's
// threshold count as one fragment's.
fn same_fragment(a: GSample, b: GSample) -> bool {
    if SURFACE_IDS {
        return a.id == b.id;
    }
    var depth = a.view_depth == b.view_depth;
    if !STORED_VIEW_DEPTH {
        depth = !depth_step(a.view_depth, b.view_depth);
    }
    return all(a.albedo == b.albedo) && a.occlusion == b.occlusion && all(a.normal == b.normal)
        && a.metallic == b.metallic && a.roughness == b.roughness && a.flags == b.flags && depth;
}

// Where a fragment covering the samples of `mask` is shaded: at the mean of their
// positions and depths, which lies on the fragment's plane (clip depth is affine in
// screen space across a triangle). One sample's own position for a mask of one.
fn fragment_surface(pixel: vec2<i32>, mask: u32) -> vec3<f32> {
    var depths: array<f32, SAMPLES>;
    for (var s = 0u; s < SAMPLES; s++) {
        if (mask & (1u << s)) != 0u {
            depths[s] = sample_depth(pixel, s);
        }
    }
    return mean_point(pixel, mask, depths);
}

// fragment_surface from the samples' clip depths, read before.
fn mean_point(pixel: vec2<i32>, mask: u32, depths: array<f32, SAMPLES>) -> vec3<f32> {
    var xy = vec2<f32>(0.0);
    var depth = 0.0;
    var n = 0.0;
    for (var s = 0u; s < SAMPLES; s++) {
        if (mask & (1u << s)) != 0u {
            xy += sample_position(pixel, s);
            depth += depths[s];
            n += 1.0;
        }
    }
    return unproject(xy / n, depth / n);
}

struct EntrySurface {
    lit: bool,
    surface: Surface,
    // What the entry's samples emit, where the pixel does not know it (a visibility
    // buffer's fragments other than sample 0's are rebuilt only here); 0 for a G-buffer,
    // whose pixel loaded every sample.
    emits: vec3<f32>,
}

// The surface an edge-list entry (`edge_samples`) of the tile at `origin` shades.
fn entry_surface(origin: vec2<u32>, code: u32) -> EntrySurface {
    let at = code >> 12u;
    let pixel = vec2<i32>(origin + vec2<u32>(at % TILE, at / TILE));
    return fragment_surface_of(pixel, code & 15u, (code >> 4u) & 0xffu);
}

// The surface of `pixel`'s fragment covering the samples of `mask`, sample `s` among them.
fn fragment_surface_of(pixel: vec2<i32>, s: u32, mask: u32) -> EntrySurface {
    return entry_of(pixel, s, load_fragment(pixel, s, mask), fragment_surface(pixel, mask));
}

// Sample `s`'s fragment of `pixel`, `g`, as the surface at point `p`.
fn entry_of(pixel: vec2<i32>, s: u32, g: GSample, p: vec3<f32>) -> EntrySurface {
    let lit = (g.flags & FLAG_LIT) != 0u;
    var emits = vec3<f32>(0.0);
    if SURFACE_IDS {
        emits = emitted(pixel, s, g);
    }
    // Screen-space AO, when the pass reads it, darkens the ambient term only.
    return EntrySurface(lit, with_screen_ao(surface_of(g, p), pixel), emits);
}

fn load_light(entry: u32) -> vec3<f32> {
    let slot = 3u * entry;
    return vec3<f32>(edge_light[slot], edge_light[slot + 1u], edge_light[slot + 2u]);
}

fn store_light(entry: u32, light: vec3<f32>) {
    let slot = 3u * entry;
    edge_light[slot] = light.r;
    edge_light[slot + 1u] = light.g;
    edge_light[slot + 2u] = light.b;
}

// The light of this batch's light `l` (batch_lights) at surface `s`. The tile's culling
// keeps lights that reach some point of its bounds; one that misses `s`'s point adds 0
// (incident's window): the test skips its BRDF (with 256 lights the 1x shading 0.95 ->
// 0.85 ms, the 4x 1.20 -> 1.04, at 3840x2160 on the H200:
// docs/design/compute-raster.md, run visibility-dense).
fn batch_light(s: Surface, l: u32) -> vec3<f32> {
    return reaching_light(s, lights[batch_lights[l]]);
}

// The light of point or spot light `light` at surface `s`: 0 without its BRDF where it
// cannot reach `s`'s point.
fn reaching_light(s: Surface, light: LightData) -> vec3<f32> {
    if !reaches(light, s.position) {
        return vec3<f32>(0.0);
    }
    return direct_light(s, light);
}

// What the samples of surface `e` take, lit by `light` in all: what it emits (a visibility
// buffer's surface), plus that light, no more than HALF_MAX.
fn taken_light(e: EntrySurface, light: vec3<f32>) -> vec3<f32> {
    return e.emits + min(light, vec3<f32>(HALF_MAX));
}

// `light`, the light of surface `e` from the batches before this one, with this batch's
// `count` lights (batch_lights): ambient and directional light too in the `first` batch;
// after the `last`, the light its samples take (no more than HALF_MAX), with what a
// visibility buffer's surface emits (a G-buffer's pixel adds each sample's own).
fn light_batch(e: EntrySurface, light: vec3<f32>, first: bool, last: bool, count: u32) -> vec3<f32> {
    var sum = select(light, vec3<f32>(0.0), first);
    if e.lit {
        if first {
            sum = ambient_and_directional(e.surface);
        }
        for (var l = 0u; l < count; l++) {
            sum += batch_light(e.surface, l);
        }
    }
    if last {
        sum = taken_light(e, sum);
    }
    return sum;
}

// Lights edge-list entry `entry` with this batch's `count` lights, in its edge_light slot.
fn shade_entry(origin: vec2<u32>, entry: u32, first: bool, last: bool, count: u32) {
    let e = entry_surface(origin, edge_samples[entry]);
    store_light(entry, light_batch(e, load_light(entry), first, last, count));
}

// Whether this dispatch lights edge-list entries: a pixel of more than one sample whose
// edge pixels are not listed for a dispatch of their own.
fn entries_here() -> bool {
    return SAMPLES > 1u && !EDGES_LISTED;
}

// A pixel's fragments, packed four bits per sample: the first sample holding the same
// fragment as sample `s` (fragment_leaders).
fn leader_of(leaders: u32, s: u32) -> u32 {
    return (leaders >> (4u * s)) & 15u;
}

// The sample whose light sample `s` takes: 0 on a non-edge pixel, else itself, or with
// ADAPTIVE its fragment's first sample.
fn source_of(leaders: u32, edge: bool, s: u32) -> u32 {
    return select(0u, select(s, leader_of(leaders, s), ADAPTIVE), edge);
}

// The samples that take sample `source`'s light.
fn source_mask(leaders: u32, edge: bool, source: u32) -> u32 {
    var mask = 0u;
    for (var s = 0u; s < SAMPLES; s++) {
        mask |= u32(source_of(leaders, edge, s) == source) << s;
    }
    return mask;
}

// Whether sample `s` (`gs`) makes its pixel an edge pixel, beside sample 0 (`g0`).
fn sample_is_edge(g0: GSample, gs: GSample, s: u32) -> bool {
    if SAMPLES == 1u {
        return false;
    }
    switch DETECTOR {
        case 0u: {
            return s > 0u && differ(g0, gs);
        }
        case 1u: {
            return (gs.edge_bits & EDGE_BIT) != 0u;
        }
        case 2u: {
            return true;
        }
        case 4u: {
            return gs.id != g0.id;
        }
        default: {
            return false;
        }
    }
}


// Clears the tile's shared state (invocation `local` 0), before a barrier.
fn start_tile(local: u32) {
    if local == 0u {
        atomicStore(&nearest_key, 0u);
        atomicStore(&farthest_key, 0u);
        atomicStore(&edge_count, 0u);
        atomicStore(&batch_light_count, 0u);
    }
}

// The tile's depth bounds, once every point it shades is in. A tile without lit samples
// has none (its keys are still 0): nothing to cull for.
struct Bounds {
    lit: bool,
    nearest: f32,
    farthest: f32,
}

fn tile_bounds() -> Bounds {
    return Bounds(atomicLoad(&farthest_key) != 0u, -key_depth(atomicLoad(&nearest_key)), key_depth(atomicLoad(&farthest_key)));
}

// Adds light `index` to this batch's lights (batch_lights) if it is one and may reach
// the tile, or every light without CULL.
fn cull_batch(index: u32, bounds: Bounds) {
    if index < light_count() && (!CULL || (bounds.lit && reaches_tile(lights[index], bounds.nearest, bounds.farthest))) {
        batch_lights[atomicAdd(&batch_light_count, 1u)] = index;
    }
}

// A resolve's weighted sum of sample colours (rgb) and of weights (a), with colour `c`
// added: clamped to what the output holds, weighted 1 (box) or by its tone-mapped
// weight.
fn resolve_sample(sum: vec4<f32>, c: vec3<f32>) -> vec4<f32> {
    let clamped = clamp(c, vec3<f32>(0.0), vec3<f32>(HALF_MAX));
    let w = select(1.0, 1.0 / (1.0 + EXPOSURE * luminance(clamped)), RESOLVE == 1u);
    return sum + vec4<f32>(w * clamped, w);
}

@compute @workgroup_size(TILE, TILE, 1)
fn cs_light_tiled(
    @builtin(workgroup_id) tile: vec3<u32>,
    @builtin(local_invocation_id) local_id: vec3<u32>,
    @builtin(local_invocation_index) local: u32,
) {
    let origin = tile.xy * TILE;
    let pixel = vec2<i32>(origin + local_id.xy);
    let inside = all(pixel < vec2<i32>(textureDimensions(out_tex)));

    start_tile(local);
    workgroupBarrier();

    // 1. Classify, a sample at a time, holding only sample 0's surface (a 4x pixel's
    // surfaces held at once took local memory), and the rest as bits (`leaders`, `lit`,
    // `entries`) rather than arrays indexed by sample. A G-buffer's samples are each
    // loaded, and compared where ADAPTIVE or the fragments view needs it; a visibility
    // buffer knows its fragments from IDs and rebuilds only sample 0's triangle here:
    // the others are rebuilt once, by the invocation that shades their edge-list entry.
    // `emits[s]` is what sample s emits (a visibility buffer's samples of sample 0's
    // triangle all emit emits[0]), and bit s of `lit` says whether its surface is lit.
    var g0: GSample;
    var leaders = 0u;
    var emits: array<vec3<f32>, SAMPLES>;
    var lit = 0u;
    var edge = false;
    // A listed edge pixel is known from its flag alone: nothing else of it is read here.
    let listed = inside && listed_edge(pixel);
    if listed {
        edge = true;
    } else if inside && SURFACE_IDS {
        // Where edge pixels are listed, the others show one triangle.
        if !EDGES_LISTED {
            leaders = fragment_leaders(pixel);
            for (var s = 1u; s < SAMPLES; s++) {
                let leader = leader_of(leaders, s);
                if leader == s {
                    lit |= u32(sample_lit(pixel, s)) << s;
                }
                edge = edge || leader != 0u;
            }
        }
        g0 = load_fragment(pixel, 0u, source_mask(leaders, true, 0u));
        emits[0] = emitted(pixel, 0u, g0);
        lit |= u32((g0.flags & FLAG_LIT) != 0u);
    } else if inside {
        for (var s = 0u; s < SAMPLES; s++) {
            let gs = load_gsample(pixel, s);
            if s == 0u {
                g0 = gs;
            }
            edge = edge || sample_is_edge(g0, gs, s);
            var leader = s;
            if ADAPTIVE || VIEW == VIEW_FRAGMENTS {
                for (var j = 0u; j < s; j++) {
                    if leader_of(leaders, j) == j && same_fragment(load_gsample(pixel, j), gs) {
                        leader = j;
                        break;
                    }
                }
            }
            leaders |= leader << (4u * s);
            emits[s] = emitted(pixel, s, gs);
            lit |= u32((gs.flags & FLAG_LIT) != 0u) << s;
        }
    }
    var fragments = 1u;
    // The samples after 0 that lead an edge-list entry.
    var entries = 0u;
    // A visibility buffer's pixel of one triangle is one fragment; a G-buffer's samples
    // may hold several where its detector sees no edge (the fragments view counts them).
    if edge || !SURFACE_IDS {
        fragments = 0u;
        for (var s = 0u; s < SAMPLES; s++) {
            fragments += u32(leader_of(leaders, s) == s);
            entries |= u32(s > 0u && source_of(leaders, edge, s) == s) << s;
        }
    }
    // A listed edge pixel is lit and stored by the edge dispatch: this one leaves it out,
    // of its depth bounds too.
    list_edge_pixel(local, pixel, listed);
    let here = inside && !listed;
    let lit0 = here && (lit & 1u) != 0u;
    var p0 = vec3<f32>(0.0);
    if lit0 {
        // A stored view depth, and a visibility buffer's triangle rebuilt at the pixel
        // center, say where the center's surface is; a depth buffer's samples say it by
        // their mean (fragment_surface): the mean of the standard sample positions is the
        // center.
        if edge || !(STORED_VIEW_DEPTH || SURFACE_IDS) {
            p0 = fragment_surface(pixel, source_mask(leaders, edge, 0u));
        } else {
            p0 = surface_position(vec2<f32>(pixel) + 0.5, g0.view_depth);
        }
        include_depth(p0);
    }
    var base = 0u;
    if here && edge && entries_here() {
        base = atomicAdd(&edge_count, countOneBits(entries));
        var next = base;
        for (var s = 1u; s < SAMPLES; s++) {
            if ((entries >> s) & 1u) != 0u {
                let mask = source_mask(leaders, edge, s);
                edge_samples[next] = (local << 12u) | (mask << 4u) | s;
                next++;
                if ((lit >> s) & 1u) != 0u {
                    include_depth(fragment_surface(pixel, mask));
                }
            }
        }
    }
    set_side_plane(vec2<f32>(origin), vec2<f32>(f32(TILE)), local);
    workgroupBarrier();

    // The edge-list entries this invocation shades, as surfaces.
    let edges = atomicLoad(&edge_count);
    let bounds = tile_bounds();
    // Sample 0's light accumulates in registers, an edge entry's in its edge_light
    // slot (each entry is one invocation's), so that no invocation holds light for
    // entries it is not shading. An entry's surface is loaded again for each batch
    // rather than held through it (a visibility buffer rebuilds its triangle each time);
    // the first batch adds the ambient and directional light, the last writes what the
    // pixel reads.
    let surface0 = with_screen_ao(surface_of(g0, p0), pixel);
    var light0 = vec3<f32>(0.0);
    if VIEW == VIEW_SHADED && lit0 {
        light0 = ambient_and_directional(surface0);
    }

    // 2 and 3. Point and spot lights (after the directional ones), a batch at a time; one
    // batch at least, which lights the edge entries' ambient and directional light.
    var tile_lights = directional_count();
    if VIEW == VIEW_SHADED || VIEW == VIEW_TILE_LIGHTS {
        let first = directional_count();
        let last = max(light_count(), first + 1u);
        for (var batch = first; batch < last; batch += THREADS) {
            cull_batch(batch + local, bounds);
            workgroupBarrier();
            let count = atomicLoad(&batch_light_count);
            tile_lights += count;
            if VIEW == VIEW_SHADED {
                if lit0 {
                    for (var l = 0u; l < count; l++) {
                        light0 += batch_light(surface0, l);
                    }
                }
                if entries_here() {
                    for (var entry = local; entry < edges; entry += THREADS) {
                        shade_entry(origin, entry, batch == first, batch + THREADS >= last, count);
                    }
                }
            }
            workgroupBarrier();
            if local == 0u {
                atomicStore(&batch_light_count, 0u);
            }
            workgroupBarrier();
        }
    }
    workgroupBarrier();
    if !here {
        return;
    }

    let covered = g0.view_depth > 0.0;
    switch VIEW {
        case VIEW_EDGES: {
            let color = select(select(vec3<f32>(0.0), vec3<f32>(0.0, 0.0, 1.0), covered), vec3<f32>(1.0, 0.0, 0.0), edge);
            textureStore(out_tex, pixel, vec4<f32>(color, 1.0));
        }
        case VIEW_TILE_LIGHTS: {
            let color = select(heat(f32(tile_lights - 1u) / max(HEAT_MAX - 1.0, 1.0)), vec3<f32>(0.0), tile_lights == 0u);
            textureStore(out_tex, pixel, vec4<f32>(color, 1.0));
        }
        case VIEW_SHADOWS: {
            let color = select(vec3<f32>(0.0), vec3<f32>(first_shadow_visibility(surface0)), lit0);
            textureStore(out_tex, pixel, vec4<f32>(color, 1.0));
        }
        case VIEW_CASCADES: {
            let color = select(vec3<f32>(0.0), cascade_color(surface0), lit0);
            textureStore(out_tex, pixel, vec4<f32>(color, 1.0));
        }
        case VIEW_FRAGMENTS: {
            var color = select(vec3<f32>(0.0), vec3<f32>(0.1), covered);
            if fragments == 2u {
                color = vec3<f32>(0.0, 1.0, 0.0);
            } else if fragments == 3u {
                color = vec3<f32>(0.0, 0.0, 1.0);
            } else if fragments >= 4u {
                color = vec3<f32>(1.0, 0.0, 0.0);
            }
            textureStore(out_tex, pixel, vec4<f32>(color, 1.0));
        }
        default: {
            // 4. Each sample's light is its source sample's: sample 0's in registers, the
            // others' in the edge list from `base` on, in sample order (with what a
            // visibility buffer's entry emits).
            // A visibility buffer's pixel of one triangle: every sample takes sample 0's.
            if SURFACE_IDS && !edge {
                let c = emits[0] + min(light0, vec3<f32>(HALF_MAX));
                textureStore(out_tex, pixel, vec4<f32>(clamp(c, vec3<f32>(0.0), vec3<f32>(HALF_MAX)), 1.0));
                return;
            }
            var sum = vec4<f32>(0.0);
            for (var s = 0u; s < SAMPLES; s++) {
                let source = source_of(leaders, edge, s);
                var c: vec3<f32>;
                if source == 0u {
                    c = emits[select(s, 0u, SURFACE_IDS)] + min(light0, vec3<f32>(HALF_MAX));
                } else {
                    c = load_light(base + countOneBits(entries & ((1u << source) - 1u)));
                    if !SURFACE_IDS {
                        c = emits[s] + c;
                    }
                }
                sum = resolve_sample(sum, c);
            }
            textureStore(out_tex, pixel, vec4<f32>(sum.rgb / sum.a, 1.0));
        }
    }
}
