// The scene's vertices and indices as storage (group 2, gpu_scene/geometry.rs), pulled by
// the visibility-buffer passes. Composed after common.wgsl and scene.wgsl.
//
// A vertex is scene::Vertex, 14 words: position (3 f32), normal (3 f32), uv (2 f32),
// color (4 unorm16), tangent (4 snorm16), uv1 (2 f32).
//
// The vertex buffer is bound in up to four ranges (gpu_scene/vertex_ranges.rs), so that
// a scene may hold more vertices than one storage binding does: range k holds the
// vertices from k times range 0's count on, and every range but the last as many as
// range 0. A scene one binding holds has range 0 alone (the others bind it again and are
// never read).

@group(2) @binding(0) var<storage, read> vertex_range_0: array<u32>;
@group(2) @binding(1) var<storage, read> index_words: array<u32>;
@group(2) @binding(2) var<storage, read> vertex_range_1: array<u32>;
@group(2) @binding(3) var<storage, read> vertex_range_2: array<u32>;
@group(2) @binding(4) var<storage, read> vertex_range_3: array<u32>;

const VERTEX_WORDS: u32 = 14u;

// Where a vertex's words are: the range binding them and its first word there.
struct VertexWords {
    range: u32,
    first: u32,
}

fn vertex_words(vertex: u32) -> VertexWords {
    let per_range = arrayLength(&vertex_range_0) / VERTEX_WORDS;
    let range = u32(vertex >= per_range) + u32(vertex >= 2u * per_range) + u32(vertex >= 3u * per_range);
    return VertexWords(range, (vertex - range * per_range) * VERTEX_WORDS);
}

// Word `k` of the vertex at `at`. Where one range holds the scene every invocation takes
// the same branch.
fn vertex_word(at: VertexWords, k: u32) -> u32 {
    let w = at.first + k;
    switch at.range {
        case 1u: {
            return vertex_range_1[w];
        }
        case 2u: {
            return vertex_range_2[w];
        }
        case 3u: {
            return vertex_range_3[w];
        }
        default: {
            return vertex_range_0[w];
        }
    }
}

// How a visibility buffer holds a triangle's ID + 1: in r32uint where the device
// multisamples it, else split over rg16uint (low half in red), which WebGPU multisamples.
override SPLIT_IDS: bool = true;

fn id_texel(id: u32) -> vec2<u32> {
    if SPLIT_IDS {
        return vec2<u32>(id & 0xffffu, id >> 16u);
    }
    return vec2<u32>(id, 0u);
}

fn texel_id(texel: vec4<u32>) -> u32 {
    if SPLIT_IDS {
        return texel.r | (texel.g << 16u);
    }
    return texel.r;
}

struct PulledVertex {
    position: vec3<f32>,
    normal: vec3<f32>,
    uv: vec2<f32>,
    color: vec4<f32>,
    tangent: vec4<f32>,
    uv1: vec2<f32>,
}

fn vertex_f32(at: VertexWords, k: u32) -> f32 {
    return bitcast<f32>(vertex_word(at, k));
}

// The object-space vertex at position `index` of the scene's index buffer, in `mesh`.
fn pull_vertex(index: u32, mesh: MeshData) -> PulledVertex {
    return vertex_at(u32(i32(index_words[index]) + mesh.base_vertex));
}

// Vertex `vertex` of the scene's vertex buffer (an indexed draw's vertex index: the
// index plus the draw's base vertex).
fn vertex_at(vertex: u32) -> PulledVertex {
    let w = vertex_words(vertex);
    var v: PulledVertex;
    v.position = vec3<f32>(vertex_f32(w, 0u), vertex_f32(w, 1u), vertex_f32(w, 2u));
    v.normal = vec3<f32>(vertex_f32(w, 3u), vertex_f32(w, 4u), vertex_f32(w, 5u));
    v.uv = vec2<f32>(vertex_f32(w, 6u), vertex_f32(w, 7u));
    v.color = vec4<f32>(unpack2x16unorm(vertex_word(w, 8u)), unpack2x16unorm(vertex_word(w, 9u)));
    v.tangent = vec4<f32>(unpack2x16snorm(vertex_word(w, 10u)), unpack2x16snorm(vertex_word(w, 11u)));
    v.uv1 = vec2<f32>(vertex_f32(w, 12u), vertex_f32(w, 13u));
    return v;
}

// Which mesh triangle `triangle` (index position / 3) belongs to: the last whose first
// index is at or before it (meshes lie in the index buffer in order).
fn mesh_of_triangle(triangle: u32) -> u32 {
    var low = 0u;
    var high = arrayLength(&meshes);
    while high - low > 1u {
        let middle = (low + high) / 2u;
        if meshes[middle].first_index <= 3u * triangle {
            low = middle;
        } else {
            high = middle;
        }
    }
    return low;
}

// Only the object-space position of pull_vertex's vertex: all a rasteriser needs.
fn pull_position(index: u32, mesh: MeshData) -> vec3<f32> {
    return position_at(u32(i32(index_words[index]) + mesh.base_vertex));
}

// The position of vertex `vertex` of the scene's vertex buffer.
fn position_at(vertex: u32) -> vec3<f32> {
    let w = vertex_words(vertex);
    return vec3<f32>(vertex_f32(w, 0u), vertex_f32(w, 1u), vertex_f32(w, 2u));
}
