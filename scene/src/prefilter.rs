//! The specular half of image-based lighting, precomputed on the CPU as glTF viewers do
//! (Karis 2013, "Real Shading in Unreal Engine 4"): the environment's radiance prefiltered
//! with the GGX lobe of each roughness, one roughness per cube-map mip level, and the
//! split-sum lookup table of the BRDF's scale and bias on F0 by `n·v` and roughness.
//!
//! Both use the BRDF of brdf.wgsl: perceptual roughness `r`, GGX `α = max(r, 0.045)²`, and
//! the height-correlated Smith visibility, so image-based and punctual speculars agree.

use std::f32::consts::PI;
use std::sync::OnceLock;

use glam::Vec3;

use super::environment::radiance;

/// Side of the prefiltered cube map's first mip level, in texels.
pub const CUBE_SIZE: u32 = 32;
/// Mip levels: 32 down to 1 texel; level `i` holds roughness `i / (CUBE_LEVELS - 1)`.
pub const CUBE_LEVELS: u32 = 6;
/// Side of the split-sum lookup table, in texels (`n·v` across, roughness down).
pub const LUT_SIZE: u32 = 32;

/// GGX samples per prefiltered texel and per lookup-table texel.
const SAMPLES: u32 = 256;

/// The prefiltered neutral environment (intensity 1): RGBA texels (the environment is
/// grey: R = G = B, A = 1), face after face in wgpu's cube order (+X, -X, +Y, -Y, +Z, -Z),
/// each face with its mip levels largest first. Computed once per process.
pub fn prefiltered_cube() -> &'static [[f32; 4]] {
    static CUBE: OnceLock<Vec<[f32; 4]>> = OnceLock::new();
    CUBE.get_or_init(|| {
        let mut texels = Vec::new();
        for face in 0..6 {
            for level in 0..CUBE_LEVELS {
                let size = CUBE_SIZE >> level;
                let roughness = level as f32 / (CUBE_LEVELS - 1) as f32;
                for y in 0..size {
                    for x in 0..size {
                        let u = (x as f32 + 0.5) / size as f32 * 2.0 - 1.0;
                        let v = (y as f32 + 0.5) / size as f32 * 2.0 - 1.0;
                        let l = prefilter(cube_direction(face, u, v), roughness);
                        texels.push([l, l, l, 1.0]);
                    }
                }
            }
        }
        texels
    })
}

/// The split-sum lookup table: per texel, the scale and bias `(a, b)` such that the
/// directional albedo of the specular BRDF is `f0 * a + b`; row `j` is roughness
/// `(j + 0.5) / LUT_SIZE`, column `i` is `n·v = (i + 0.5) / LUT_SIZE`. Computed once per
/// process.
pub fn split_sum_lut() -> &'static [[f32; 2]] {
    static LUT: OnceLock<Vec<[f32; 2]>> = OnceLock::new();
    LUT.get_or_init(|| {
        let mut texels = Vec::new();
        for j in 0..LUT_SIZE {
            for i in 0..LUT_SIZE {
                let n_v = (i as f32 + 0.5) / LUT_SIZE as f32;
                let roughness = (j as f32 + 0.5) / LUT_SIZE as f32;
                texels.push(split_sum(n_v, roughness));
            }
        }
        texels
    })
}

/// The direction through point `(u, v)` (each in [-1, 1], `v` down) of cube face `face`,
/// as the Vulkan and WebGPU cube-map convention maps directions to faces.
pub fn cube_direction(face: u32, u: f32, v: f32) -> Vec3 {
    let d = match face {
        0 => Vec3::new(1.0, -v, -u),
        1 => Vec3::new(-1.0, -v, u),
        2 => Vec3::new(u, 1.0, v),
        3 => Vec3::new(u, -1.0, -v),
        4 => Vec3::new(u, -v, 1.0),
        _ => Vec3::new(-u, -v, -1.0),
    };
    d.normalize()
}

/// The `i`th of `n` points of the Hammersley set in [0, 1)^2.
fn hammersley(i: u32, n: u32) -> (f32, f32) {
    (
        i as f32 / n as f32,
        i.reverse_bits() as f32 * 2.0f32.powi(-32),
    )
}

/// GGX `α²` for perceptual roughness `r`, clamped as brdf.wgsl clamps it.
fn alpha2(roughness: f32) -> f32 {
    roughness.max(0.045).powi(4)
}

/// A half vector around `n` drawn from the GGX distribution of `alpha2` by the sample
/// point `xi`.
fn ggx_half_vector(xi: (f32, f32), alpha2: f32, n: Vec3) -> Vec3 {
    let phi = 2.0 * PI * xi.0;
    let cos_theta = ((1.0 - xi.1) / (1.0 + (alpha2 - 1.0) * xi.1)).sqrt();
    let sin_theta = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
    let (tangent, bitangent) = n.any_orthonormal_pair();
    (tangent * phi.cos() * sin_theta + bitangent * phi.sin() * sin_theta + n * cos_theta)
        .normalize()
}

/// The neutral environment's radiance (intensity 1) around `n` weighted by the GGX lobe
/// of `roughness`, with Karis's assumption `v = r = n` (and weighted by `n·l`, as he found
/// closer to the reference): what [`prefiltered_cube`] holds at `n` in the mip level of
/// `roughness`.
pub fn prefilter(n: Vec3, roughness: f32) -> f32 {
    if roughness == 0.0 {
        return radiance(n);
    }
    let a2 = alpha2(roughness);
    let (mut sum, mut weight) = (0.0, 0.0);
    for i in 0..SAMPLES {
        let h = ggx_half_vector(hammersley(i, SAMPLES), a2, n);
        let l = 2.0 * n.dot(h) * h - n;
        let n_l = n.dot(l);
        if n_l > 0.0 {
            sum += radiance(l) * n_l;
            weight += n_l;
        }
    }
    sum / weight.max(1e-6)
}

/// brdf.wgsl's height-correlated Smith visibility term.
fn visibility(n_v: f32, n_l: f32, a2: f32) -> f32 {
    0.5 / (n_l * (n_v * n_v * (1.0 - a2) + a2).sqrt() + n_v * (n_l * n_l * (1.0 - a2) + a2).sqrt())
}

/// `(a, b)` with `∫ f_spec(l) (n·l) dl = f0 * a + b` for Schlick's Fresnel, by GGX
/// importance sampling: each sample weighs `F * V * (n·l) * 4 (v·h) / (n·h)`. What
/// [`split_sum_lut`] holds at `(n_v, roughness)`.
pub fn split_sum(n_v: f32, roughness: f32) -> [f32; 2] {
    let a2 = alpha2(roughness);
    let n = Vec3::Z;
    let v = Vec3::new((1.0 - n_v * n_v).sqrt(), 0.0, n_v);
    let (mut a, mut b) = (0.0, 0.0);
    for i in 0..SAMPLES {
        let h = ggx_half_vector(hammersley(i, SAMPLES), a2, n);
        let l = 2.0 * v.dot(h) * h - v;
        let (n_l, n_h, v_h) = (l.z, h.z.max(0.0), v.dot(h).max(0.0));
        if n_l > 0.0 && n_h > 0.0 {
            let weight = visibility(n_v, n_l, a2) * n_l * 4.0 * v_h / n_h;
            let fresnel = (1.0 - v_h).powi(5);
            a += (1.0 - fresnel) * weight;
            b += fresnel * weight;
        }
    }
    [a / SAMPLES as f32, b / SAMPLES as f32]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_face_center_looks_along_its_axis() {
        let axes = [Vec3::X, -Vec3::X, Vec3::Y, -Vec3::Y, Vec3::Z, -Vec3::Z];
        for (face, axis) in axes.into_iter().enumerate() {
            assert_eq!(cube_direction(face as u32, 0.0, 0.0), axis);
        }
        // +Z's top row looks up, its left column toward -X.
        assert!(cube_direction(4, 0.0, -0.9).y > 0.5);
        assert!(cube_direction(4, -0.9, 0.0).x < -0.5);
    }

    #[test]
    fn the_split_sum_is_a_directional_albedo_at_most_one() {
        for &[a, b] in split_sum_lut() {
            assert!(a >= 0.0 && b >= 0.0 && a + b <= 1.02, "a {a} b {b}");
        }
        // Smooth and head-on: nearly all of F0 comes back, almost no bias.
        let [a, b] = split_sum(1.0, 0.05);
        assert!((a - 1.0).abs() < 0.05 && b < 0.02, "a {a} b {b}");
    }

    #[test]
    fn prefiltering_keeps_the_mirror_and_blurs_toward_the_surroundings() {
        let down = -Vec3::Y;
        assert_eq!(prefilter(down, 0.0), radiance(down));
        // Underfoot is the darkest part of the studio, the key soft box the brightest: a
        // wide lobe sees brighter parts around the one, darker around the other.
        let (mirror, rough) = (prefilter(down, 0.0), prefilter(down, 1.0));
        assert!(rough > mirror, "underfoot: mirror {mirror} rough {rough}");
        let key = Vec3::new(-0.5, 0.75, 0.45).normalize();
        let (mirror, rough) = (prefilter(key, 0.0), prefilter(key, 1.0));
        assert!(
            rough < mirror && rough > 0.5,
            "key: mirror {mirror} rough {rough}"
        );
        let texels = prefiltered_cube().len() as u32;
        let per_face: u32 = (0..CUBE_LEVELS).map(|l| (CUBE_SIZE >> l).pow(2)).sum();
        assert_eq!(texels, 6 * per_face);
    }
}
