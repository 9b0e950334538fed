// A visibility buffer's edge pixels, lit by a dispatch of their own (light_tiled.rs says
// when): cs_light_tiled knows them from sample 0's flag alone and lists them across the
// output, one atomic a tile; cs_light_edge_pixels lights them EDGE_INVOCATIONS at a time,
// with the lights that reach those pixels' samples (each run culling them where the scene
// has many, runs_cull), and resolves them. The tiles' dispatch carries no code for their
// fragments, and every warp of this one is full
// (docs/design/compute-raster.md, run visibility-edges measured a tile's edge entries in a second round
// of its first warps while the others waited).
//
// Composed after light_tiled.wgsl, a visibility buffer's reader (`one_surface`,
// `sample_id`, `sample_depth`) and visibility_read.wgsl (`read_samples`, `leaders_of`,
// `joined_gsample`).

const EDGES_LISTED: bool = true;

// The edge pixels listed: their count, then each pixel's x | y << 16. light_tiled.rs owns
// the buffer, with room for every pixel of the output, and empties it
// (cs_edge_pixels_reset) before cs_light_tiled fills it.
struct EdgePixels {
    count: atomic<u32>,
    pixels: array<u32>,
}
@group(1) @binding(12) var<storage, read_write> edge_pixels: EdgePixels;

// The first of the tile's room in the list.
var<workgroup> tile_edges_base: u32;

fn listed_edge(pixel: vec2<i32>) -> bool {
    return !one_surface(pixel);
}

// Lists `pixel` if `listed`: the tile counts its edge pixels (edge_count), takes room for
// them with one atomic, then each invocation writes its own.
fn list_edge_pixel(local: u32, pixel: vec2<i32>, listed: bool) {
    var slot = 0u;
    if listed {
        slot = atomicAdd(&edge_count, 1u);
    }
    workgroupBarrier();
    if local == 0u {
        tile_edges_base = atomicAdd(&edge_pixels.count, atomicLoad(&edge_count));
    }
    let base = workgroupUniformLoad(&tile_edges_base);
    if listed {
        edge_pixels.pixels[base + slot] = u32(pixel.x) | (u32(pixel.y) << 16u);
    }
}

@compute @workgroup_size(1, 1, 1)
fn cs_edge_pixels_reset() {
    atomicStore(&edge_pixels.count, 0u);
}

// cs_light_edge_pixels' workgroup: a run of EDGE_INVOCATIONS listed pixels (near each
// other, as tiles list them), culled for together as a tile is. On the H200 at 3840x2160
// dense's 4x tiled pass takes 0.74 ms with runs of 128, 0.77 with 64, 0.81 with 32 and
// 0.75 with 256 (where 256 lights' goes from 1.04 to 1.08; 1.05 with 128): a run's
// culling is shared by more pixels, and its rectangle still fits its lights
// (docs/design/compute-raster.md, run visibility-merged).
const EDGE_INVOCATIONS: u32 = min(THREADS, 128u);
var<workgroup> edge_total: u32;
// The run's pixels' bounding rectangle: smallest x and y, largest x and y.
var<workgroup> run_bounds: array<atomic<u32>, 4>;
// Each invocation's fragments' light between batches of lights, red, green and blue of
// its fragment led by sample s at 3 (invocation * SAMPLES + s) and on.
var<workgroup> fragment_light: array<f32, 3u * EDGE_INVOCATIONS * SAMPLES>;

// Lights and resolves the listed edge pixels: the workgroups take runs of
// EDGE_INVOCATIONS pixels in turn, as many workgroups apart as light_tiled.rs dispatches.
@compute @workgroup_size(EDGE_INVOCATIONS, 1, 1)
fn cs_light_edge_pixels(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) local: u32,
) {
    if local == 0u {
        edge_total = atomicLoad(&edge_pixels.count);
    }
    let count = workgroupUniformLoad(&edge_total);
    let culls = runs_cull();
    for (var run = group.x * EDGE_INVOCATIONS; run < count; run += groups.x * EDGE_INVOCATIONS) {
        if culls {
            light_run(run, count, local);
        } else if run + local < count {
            light_unculled(listed_pixel(run + local));
        }
    }
}

// Whether each run culls the point and spot lights for its pixels as a tile does
// (light_run), or each fragment tests every light (light_unculled): more than
// RUN_CULL_ABOVE lights. With few, the run's depth bounds, side planes and barriers cost
// more than the tests they save. On the H200 at 3840x2160, 4x, the tiled pass takes
// 0.69 ms unculled and 0.72 culled on builtin:dense (6 lights), 0.35 and 0.34 with
// lights?count=16, 0.41 and 0.39 with 32, 0.53 and 0.49 with 64
// (docs/design/compute-raster.md, run visibility-runs): the turn lies between 6 and 16.
const RUN_CULL_ABOVE: u32 = 8u;

fn runs_cull() -> bool {
    return CULL && light_count() - directional_count() > RUN_CULL_ABOVE;
}

// Lights and resolves listed pixel `p` with every light, no workgroup memory and no
// barrier: the samples of each fragment take its light.
fn light_unculled(p: ListedPixel) {
    var sum = vec4<f32>(0.0);
    var rest = p.fragments;
    while rest != 0u {
        let s = firstTrailingBit(rest);
        rest &= rest - 1u;
        let mask = source_mask(p.leaders, true, s);
        let e = listed_fragment(p, s, mask);
        var light = vec3<f32>(0.0);
        if e.lit {
            light = ambient_and_directional(e.surface);
            for (var l = directional_count(); l < light_count(); l++) {
                light += reaching_light(e.surface, lights[l]);
            }
        }
        sum = with_fragment(sum, mask, taken_light(e, light));
    }
    textureStore(out_tex, p.pixel, vec4<f32>(sum.rgb / sum.a, 1.0));
}

// A pixel's resolve `sum` with the samples of `mask` taking `light`.
fn with_fragment(sum: vec4<f32>, mask: u32, light: vec3<f32>) -> vec4<f32> {
    return sum + f32(countOneBits(mask)) * resolve_sample(vec4<f32>(0.0), light);
}

// Lights listed pixel `run + local`, if there is one: each of its fragments (each sample,
// or with ADAPTIVE each triangle once) rebuilt at the mean of the samples it covers, lit
// with the lights reaching the run (culled in batches of THREADS as a tile culls) and
// taken by those samples. Every invocation of the workgroup calls it (it has barriers).
fn light_run(run: u32, count: u32, local: u32) {
    start_tile(local);
    if local == 0u {
        atomicStore(&run_bounds[0], 0xffffffffu);
        atomicStore(&run_bounds[1], 0xffffffffu);
        atomicStore(&run_bounds[2], 0u);
        atomicStore(&run_bounds[3], 0u);
    }
    workgroupBarrier();
    let listed = run + local < count;
    var p: ListedPixel;
    if listed {
        p = listed_pixel(run + local);
        let pixel = p.pixel;
        // The run's depth bounds take every covered sample's point (a fragment's point,
        // the mean of its samples', lies between them), the pixel's range first.
        var nearest = 3.4e38;
        var farthest = -3.4e38;
        for (var s = 0u; s < SAMPLES; s++) {
            if p.samples.ids[s] != 0u {
                let depth = dot(unproject(sample_position(pixel, s), p.samples.depths[s]), camera.forward);
                nearest = min(nearest, depth);
                farthest = max(farthest, depth);
            }
        }
        if nearest <= farthest {
            include_depths(nearest, farthest);
        }
        atomicMin(&run_bounds[0], u32(pixel.x));
        atomicMin(&run_bounds[1], u32(pixel.y));
        atomicMax(&run_bounds[2], u32(pixel.x));
        atomicMax(&run_bounds[3], u32(pixel.y));
    }
    workgroupBarrier();
    let lowest = vec2<u32>(atomicLoad(&run_bounds[0]), atomicLoad(&run_bounds[1]));
    let highest = vec2<u32>(atomicLoad(&run_bounds[2]), atomicLoad(&run_bounds[3]));
    set_side_plane(vec2<f32>(lowest), vec2<f32>(highest - lowest + 1u), local);
    workgroupBarrier();
    let bounds = tile_bounds();

    var sum = vec4<f32>(0.0);
    let first = directional_count();
    let last = max(light_count(), first + 1u);
    for (var batch = first; batch < last; batch += THREADS) {
        for (var k = local; k < THREADS; k += EDGE_INVOCATIONS) {
            cull_batch(batch + k, bounds);
        }
        workgroupBarrier();
        let lights_now = atomicLoad(&batch_light_count);
        let last_batch = batch + THREADS >= last;
        var rest = p.fragments;
        while rest != 0u {
            let s = firstTrailingBit(rest);
            rest &= rest - 1u;
            let mask = source_mask(p.leaders, true, s);
            let slot = 3u * (local * SAMPLES + s);
            var light = vec3<f32>(fragment_light[slot], fragment_light[slot + 1u], fragment_light[slot + 2u]);
            light = light_batch(listed_fragment(p, s, mask), light, batch == first, last_batch, lights_now);
            if last_batch {
                sum = with_fragment(sum, mask, light);
            } else {
                fragment_light[slot] = light.r;
                fragment_light[slot + 1u] = light.g;
                fragment_light[slot + 2u] = light.b;
            }
        }
        workgroupBarrier();
        if local == 0u {
            atomicStore(&batch_light_count, 0u);
        }
        workgroupBarrier();
    }
    if listed {
        textureStore(out_tex, p.pixel, vec4<f32>(sum.rgb / sum.a, 1.0));
    }
}

// A listed pixel as its invocation lights it: its samples read once (its fragments' IDs
// and depths come from them, not from loads of their own: on the H200 at 3840x2160 this
// took builtin:dense's 4x shading from 0.75 to 0.71 ms, docs/design/compute-raster.md, run visibility-runs),
// its fragments' leaders, and the samples leading a fragment (a bit each).
struct ListedPixel {
    pixel: vec2<i32>,
    samples: PixelSamples,
    leaders: u32,
    fragments: u32,
}

fn listed_pixel(index: u32) -> ListedPixel {
    let packed = edge_pixels.pixels[index];
    var p: ListedPixel;
    p.pixel = vec2<i32>(vec2<u32>(packed & 0xffffu, packed >> 16u));
    p.samples = read_samples(p.pixel);
    p.leaders = leaders_of(p.pixel, p.samples);
    for (var s = 0u; s < SAMPLES; s++) {
        p.fragments |= u32(source_of(p.leaders, true, s) == s) << s;
    }
    return p;
}

// fragment_surface_of for listed pixel `p`: its fragment led by sample `s`, covering the
// samples of `mask`.
fn listed_fragment(p: ListedPixel, s: u32, mask: u32) -> EntrySurface {
    let g = joined_gsample(p.pixel, p.samples.ids, s, mask);
    return entry_of(p.pixel, s, g, mean_point(p.pixel, mask, p.samples.depths));
}
