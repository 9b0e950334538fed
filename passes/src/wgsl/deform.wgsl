// Skinning and morphing (gpu_scene/deform.rs): one invocation per vertex of a deformed
// mesh writes its deformed position, normal and tangent over the scene's vertex buffer,
// from its rest vertex, its morph targets' offsets and its joints, before any pass of the
// frame reads the buffer. Morph targets first, then the skin, as glTF orders them and as
// rgraph_scene::Deformation::deform does on the CPU. The position a vertex had is kept in
// `previous` first, for motion vectors.

// A vertex of a deformed mesh: its four joints (16 bits each), its deformation, where its
// fifth to eighth joints are (glTF's JOINTS_1 and WEIGHTS_1: an entry of `influences` past
// the deformed vertices' own, whose joints and weights are read; 0 for none), and its
// joints' weights (zero for a mesh without a skin).
struct Influence {
    joints: vec2<u32>,
    deformation: u32,
    second: u32,
    weights: vec4<f32>,
}

// One deformed mesh: where its vertices are in `rest` and `influences` (first_vertex on),
// where they go in `vertices` (word base_word on), and where its joints, weights and
// morph offsets start.
struct Deformation {
    first_vertex: u32,
    base_word: u32,
    vertex_count: u32,
    first_joint: u32,
    first_offset: u32,
    first_weight: u32,
    targets: u32,
    skinned: u32,
    first_previous: u32,
}

// The scene's vertices (rgraph_scene::Vertex, 14 words each) from the first deformed
// mesh's on.
@group(0) @binding(0) var<storage, read_write> vertices: array<u32>;
// The deformed meshes' rest vertices, one after another.
@group(0) @binding(1) var<storage, read> rest: array<u32>;
// One per deformed vertex, then the second sets of those with eight influences.
@group(0) @binding(2) var<storage, read> influences: array<Influence>;
@group(0) @binding(3) var<storage, read> deformations: array<Deformation>;
// Per morph target per vertex, nine floats: position, normal and tangent offsets.
@group(0) @binding(4) var<storage, read> offsets: array<f32>;
// This frame's joints, each in the object space of its mesh.
@group(0) @binding(5) var<storage, read> joints: array<mat4x4<f32>>;
// This frame's morph weights.
@group(0) @binding(6) var<storage, read> weights: array<f32>;
// The positions the vertices had before this dispatch (3 f32 each), from the first
// deformed mesh's first vertex on.
@group(0) @binding(7) var<storage, read_write> previous: array<f32>;

const WORDS: u32 = 14u;

fn rest_vec3(word: u32) -> vec3<f32> {
    return vec3<f32>(bitcast<f32>(rest[word]), bitcast<f32>(rest[word + 1u]), bitcast<f32>(rest[word + 2u]));
}

fn offset(at: u32) -> vec3<f32> {
    return vec3<f32>(offsets[at], offsets[at + 1u], offsets[at + 2u]);
}

fn write_vec3(word: u32, v: vec3<f32>) {
    vertices[word] = bitcast<u32>(v.x);
    vertices[word + 1u] = bitcast<u32>(v.y);
    vertices[word + 2u] = bitcast<u32>(v.z);
}

// The blend of four joints (packed two per word, numbered from `first_joint`) by `w`.
fn blend(packed: vec2<u32>, w: vec4<f32>, first_joint: u32) -> mat4x4<f32> {
    let ids = vec4<u32>(packed.x & 0xffffu, packed.x >> 16u, packed.y & 0xffffu, packed.y >> 16u) + first_joint;
    return joints[ids.x] * w.x + joints[ids.y] * w.y + joints[ids.z] * w.z + joints[ids.w] * w.w;
}

// `v` at unit length, or zero where it is zero: a zero normal asks for the face normal,
// a zero tangent for none.
fn unit_or_zero(v: vec3<f32>) -> vec3<f32> {
    let length_squared = dot(v, v);
    return select(vec3<f32>(0.0), v * inverseSqrt(length_squared), length_squared > 0.0);
}

@compute @workgroup_size(64)
fn cs_deform(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = id.x + id.y * groups.x * 64u;
    // The deformed vertices end where the last deformation's do (second sets follow).
    let last = deformations[arrayLength(&deformations) - 1u];
    if i >= last.first_vertex + last.vertex_count {
        return;
    }
    let influence = influences[i];
    let d = deformations[influence.deformation];
    let local = i - d.first_vertex;
    let r = i * WORDS;
    var position = rest_vec3(r);
    var normal = rest_vec3(r + 3u);
    let tangent_xy = unpack2x16snorm(rest[r + 10u]);
    let tangent_zw = unpack2x16snorm(rest[r + 11u]);
    var tangent = vec3<f32>(tangent_xy, tangent_zw.x);
    for (var t = 0u; t < d.targets; t++) {
        let w = weights[d.first_weight + t];
        let at = (d.first_offset + t * d.vertex_count + local) * 9u;
        position += w * offset(at);
        normal += w * offset(at + 3u);
        tangent += w * offset(at + 6u);
    }
    if d.skinned != 0u {
        var m = blend(influence.joints, influence.weights, d.first_joint);
        if influence.second != 0u {
            let more = influences[influence.second];
            m += blend(more.joints, more.weights, d.first_joint);
        }
        let linear = mat3x3<f32>(m[0].xyz, m[1].xyz, m[2].xyz);
        // The cofactor matrix: normals move by the inverse transpose, up to length.
        let cofactor = mat3x3<f32>(cross(linear[1], linear[2]), cross(linear[2], linear[0]), cross(linear[0], linear[1]));
        position = (m * vec4<f32>(position, 1.0)).xyz;
        normal = cofactor * normal;
        tangent = linear * tangent;
    }
    let out = d.base_word + local * WORDS;
    let kept = (d.first_previous + local) * 3u;
    for (var c = 0u; c < 3u; c++) {
        previous[kept + c] = bitcast<f32>(vertices[out + c]);
    }
    write_vec3(out, position);
    write_vec3(out + 3u, unit_or_zero(normal));
    let unit_tangent = unit_or_zero(tangent);
    vertices[out + 10u] = pack2x16snorm(unit_tangent.xy);
    vertices[out + 11u] = pack2x16snorm(vec2<f32>(unit_tangent.z, tangent_zw.y));
}
