// The scene's vertices and indices as storage (group 2, gpu_scene/geometry.rs), pulled by
// the visibility-buffer passes. Composed after common.wgsl and scene.wgsl.
//
// A vertex is scene::Vertex, 14 words: position (3 f32), normal (3 f32), uv (2 f32),
// color (4 unorm16), tangent (4 snorm16), uv1 (2 f32).

@group(2) @binding(0) var<storage, read> vertex_words: array<u32>;
@group(2) @binding(1) var<storage, read> index_words: array<u32>;

const VERTEX_WORDS: u32 = 14u;

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

fn vertex_f32(w: u32) -> f32 {
    return bitcast<f32>(vertex_words[w]);
}

// The object-space vertex at position `index` of the scene's index buffer, in `mesh`.
fn pull_vertex(index: u32, mesh: MeshData) -> PulledVertex {
    return vertex_at(u32(i32(index_words[index]) + mesh.base_vertex));
}

// Vertex `vertex` of the scene's vertex buffer (an indexed draw's vertex index: the
// index plus the draw's base vertex).
fn vertex_at(vertex: u32) -> PulledVertex {
    let w = vertex * VERTEX_WORDS;
    var v: PulledVertex;
    v.position = vec3<f32>(vertex_f32(w), vertex_f32(w + 1u), vertex_f32(w + 2u));
    v.normal = vec3<f32>(vertex_f32(w + 3u), vertex_f32(w + 4u), vertex_f32(w + 5u));
    v.uv = vec2<f32>(vertex_f32(w + 6u), vertex_f32(w + 7u));
    v.color = vec4<f32>(unpack2x16unorm(vertex_words[w + 8u]), unpack2x16unorm(vertex_words[w + 9u]));
    v.tangent = vec4<f32>(unpack2x16snorm(vertex_words[w + 10u]), unpack2x16snorm(vertex_words[w + 11u]));
    v.uv1 = vec2<f32>(vertex_f32(w + 12u), vertex_f32(w + 13u));
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
    let w = vertex * VERTEX_WORDS;
    return vec3<f32>(vertex_f32(w), vertex_f32(w + 1u), vertex_f32(w + 2u));
}
