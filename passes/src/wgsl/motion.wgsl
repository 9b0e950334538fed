// Motion vectors (passes/motion_vectors.rs): per pixel, where the surface it shows was in
// the previous frame, as this frame's position minus that one, in pixels (x right, y
// down), both without the camera's jitter. Composed after common.wgsl and scene.wgsl,
// then a block defining `pixel_motion(pixel)`: motion_objects.wgsl (a visibility buffer:
// each pixel's triangle, moved by its mesh's transforms) or motion_depth.wgsl (a depth
// buffer: static points, moved by the camera alone), with what it reads in group 1.
// `pixel_motion` also gives the surface's view depth (FAR_AWAY where nothing was drawn),
// which the motion texture keeps in blue: a temporal filter takes the front-most motion
// of a neighbourhood by it; and in alpha the view depth the same point had in the
// previous frame, which a temporal filter compares with the previous frame's blue where
// the point was (a history of this texture): nearer there, another surface hid the point
// (disocclusion), and the history shows that surface.

// The frame's matrices, written by the pass before each frame (gpu_scene's camera is
// jittered; these are not). `current` and `previous` take a point relative to this
// frame's camera (w = 1) or a direction (w = 0) that stays put in the world to this and
// the previous frame's clip space; per mesh, `objects[2m]` and `objects[2m + 1]` take an
// object-space point to this and the previous frame's clip space (from a depth buffer:
// this frame's camera-relative point). `deformed`: where this frame's skins and morph
// targets moved vertices (z = 1), the scene's vertices x..y have their previous positions
// in motion_objects.wgsl's `replaced`, and a G-buffer's pose offset holds the last pose
// (motion_pose.wgsl). `depth_before` and `w_before` take a point in the previous frame's
// clip space to its view depth then: their products' quotient (the previous camera's
// inverse projection, perspective or orthographic).
struct Motion {
    current: mat4x4<f32>,
    previous: mat4x4<f32>,
    deformed: vec4<u32>,
    depth_before: vec4<f32>,
    w_before: vec4<f32>,
    objects: array<mat4x4<f32>>,
}

@group(1) @binding(9) var<storage, read_write> motion: Motion;
@group(1) @binding(7) var out_tex: OutTex;

// 1: the debug view (rgba8unorm, 0.5 + motion / VIEW_RANGE per axis, blue 0.5); 0: the
// motion itself (rgba16float: x, y, view depth, previous view depth).
override VIEW: u32 = 0u;
const VIEW_RANGE: f32 = 32.0;
// The view depth of a pixel where nothing was drawn: the largest finite half float.
const FAR_AWAY: f32 = 65504.0;

// The view depth of `p`, a point relative to this frame's (jittered) camera.
fn view_depth(p: vec3<f32>) -> f32 {
    return min(dot(p, camera.forward), FAR_AWAY);
}

// The pixel coordinate of clip-space point `clip`.
fn to_pixel(clip: vec4<f32>) -> vec2<f32> {
    let ndc = clip.xy / clip.w;
    return vec2<f32>(ndc.x * 0.5 + 0.5, 0.5 - ndc.y * 0.5) * camera.viewport;
}

// The motion of a point at `now` in this frame's clip space and `before` in the
// previous frame's, and its view depth then (FAR_AWAY at most).
fn moved(now: vec4<f32>, before: vec4<f32>) -> vec3<f32> {
    let depth = dot(motion.depth_before, before) / dot(motion.w_before, before);
    return vec3<f32>(to_pixel(now) - to_pixel(before), min(depth, FAR_AWAY));
}

// The motion of `p`, a point (w = 1) relative to this frame's camera, that stays put in
// the world, and its previous view depth.
fn static_motion(p: vec4<f32>) -> vec3<f32> {
    return moved(motion.current * p, motion.previous * p);
}

// The motion where nothing was drawn: the direction of the ray through pixel coordinate
// `at`, which only the camera's turn moves; FAR_AWAY in both frames.
fn sky_motion(at: vec2<f32>) -> vec4<f32> {
    return vec4<f32>(static_motion(vec4<f32>(ray_direction(at), 0.0)).xy, FAR_AWAY, FAR_AWAY);
}

// The direction of the ray through pixel coordinate `at` (either way along it: a
// direction's clip position and its opposite's divide to the same point).
fn ray_direction(at: vec2<f32>) -> vec3<f32> {
    return unproject(at, 0.25) - unproject(at, 0.5);
}

@compute @workgroup_size(8, 8)
fn cs_motion(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(out_tex);
    if any(id.xy >= size) {
        return;
    }
    let m = pixel_motion(vec2<i32>(id.xy));
    var out = m;
    if VIEW == 1u {
        out = vec4<f32>(clamp(0.5 + m.xy / VIEW_RANGE, vec2<f32>(0.0), vec2<f32>(1.0)), 0.5, 1.0);
    }
    textureStore(out_tex, vec2<i32>(id.xy), out);
}
