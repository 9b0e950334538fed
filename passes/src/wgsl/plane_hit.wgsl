// A triangle seen through a pixel, from the scene's geometry: where the pixel's ray meets
// the triangle's plane, as barycentrics, and how they change one pixel over (ray
// differentials), for the passes that rebuild a triangle's attributes without a raster's
// interpolation (visibility_read.wgsl's shading, mask_texture.wgsl's alpha test).
// Composed after scene.wgsl, geometry.wgsl and material_table.wgsl (TexCoords).

// Where the ray through pixel coordinate `at` meets the plane of the triangle at `p0`
// with edges `e1` and `e2` (Möller-Trumbore; the ray from two unprojected points: any
// projection): the barycentrics there, inside the triangle or not (the plane's, so one
// pixel over they give the texture coordinates' change per pixel), the ray, and the
// distance along it.
struct PlaneHit {
    b: vec3<f32>,
    origin: vec3<f32>,
    ray: vec3<f32>,
    along: f32,
}

fn hit_plane(at: vec2<f32>, p0: vec3<f32>, e1: vec3<f32>, e2: vec3<f32>) -> PlaneHit {
    let origin = unproject(at, 0.5);
    let ray = unproject(at, 0.25) - origin;
    let pv = cross(ray, e2);
    // A triangle seen edge-on covers no sample, so the determinant is never 0 here.
    let inverse = 1.0 / dot(e1, pv);
    let t = origin - p0;
    let q = cross(t, e1);
    let u = dot(t, pv) * inverse;
    let v = dot(ray, q) * inverse;
    return PlaneHit(vec3<f32>(1.0 - u - v, u, v), origin, ray, dot(e2, q) * inverse);
}

// The texture coordinates of vertices `v0`, `v1`, `v2` at barycentrics `b`.
fn tex_coords(b: vec3<f32>, v0: PulledVertex, v1: PulledVertex, v2: PulledVertex) -> TexCoords {
    return TexCoords(b.x * v0.uv + b.y * v1.uv + b.z * v2.uv, b.x * v0.uv1 + b.y * v1.uv1 + b.z * v2.uv1);
}

// The barycentrics of the plane one pixel right and one down from `b` (the plane's at
// `at`): their change across the 2x2 quad `at` lies in (from its even corner, keeping
// `at`'s place in the pixel), as a fragment shader's coarse derivatives are taken.
// Lavapipe's are; differences at the pixel itself would pick other mip levels where the
// change varies from pixel to pixel (a grazing floor).
struct QuadSteps {
    right: vec3<f32>,
    down: vec3<f32>,
}

fn quad_steps(at: vec2<f32>, b: vec3<f32>, p0: vec3<f32>, e1: vec3<f32>, e2: vec3<f32>) -> QuadSteps {
    let quad = at - vec2<f32>(vec2<u32>(at) & vec2<u32>(1u));
    let base = hit_plane(quad, p0, e1, e2).b;
    return QuadSteps(
        b + hit_plane(quad + vec2<f32>(1.0, 0.0), p0, e1, e2).b - base,
        b + hit_plane(quad + vec2<f32>(0.0, 1.0), p0, e1, e2).b - base,
    );
}
