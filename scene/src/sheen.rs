//! KHR_materials_sheen's lobe on the CPU, for the lookup table the shaders scale the base
//! by: the directional albedo `E(n·v, roughness)` of the sheen BRDF of colour 1, Estevez
//! and Kulla's "Charlie" distribution with the visibility term the glTF sample viewer
//! uses (their fitted Λ; brdf.wgsl evaluates the same functions). A surface whose sheen
//! reflects `max(colour) · E` of the light keeps `1 - max(colour) · E` for the base
//! (the extension's albedo scaling).

use std::sync::OnceLock;

use glam::Vec3;

use super::prefilter::LUT_SIZE;

/// Charlie-distributed half vectors per lookup-table texel.
const SAMPLES: u32 = 1024;

/// The smallest roughness the lobe is evaluated at (the sample viewer's clamp): the
/// distribution's exponent is 1 / roughness².
const MIN_ROUGHNESS: f32 = 1e-6;

/// The sheen distribution at `n_h` for perceptual `roughness`:
/// `(2 + 1/α) sin(θh)^(1/α) / 2π`, α = roughness².
pub fn charlie(roughness: f32, n_h: f32) -> f32 {
    let alpha = roughness.max(MIN_ROUGHNESS).powi(2);
    let sin2 = (1.0 - n_h * n_h).max(0.0);
    (2.0 + 1.0 / alpha) * sin2.powf(0.5 / alpha) / (2.0 * std::f32::consts::PI)
}

/// Estevez and Kulla's fitted exponent of their Λ at cosine `x` for α `alpha`.
fn lambda_exponent(x: f32, alpha: f32) -> f32 {
    let t = (1.0 - alpha) * (1.0 - alpha);
    let mix = |a: f32, b: f32| a + (b - a) * t;
    mix(21.5473, 25.3245) / (1.0 + mix(3.82987, 3.32435) * x.powf(mix(0.19823, 0.16801)))
        + mix(-1.97760, -1.27393) * x
        + mix(-4.32054, -4.85967)
}

fn lambda(cos: f32, alpha: f32) -> f32 {
    if cos.abs() < 0.5 {
        lambda_exponent(cos, alpha).exp()
    } else {
        (2.0 * lambda_exponent(0.5, alpha) - lambda_exponent(1.0 - cos, alpha)).exp()
    }
}

/// The sheen visibility term (the masking and the `1 / (4 n·l n·v)` of a microfacet
/// BRDF), at most 1.
pub fn sheen_visibility(n_l: f32, n_v: f32, roughness: f32) -> f32 {
    let alpha = roughness.max(MIN_ROUGHNESS).powi(2);
    let denominator = (1.0 + lambda(n_v, alpha) + lambda(n_l, alpha)) * 4.0 * n_v * n_l;
    (1.0 / denominator).clamp(0.0, 1.0)
}

/// The directional albedo of the sheen lobe of colour 1 seen at `n_v`: `∫ D V (n·l) dl`,
/// by sampling half vectors from the Charlie distribution (`sin θh = ξ^(α / (2α + 1))`,
/// whose density is `D (n·h)`), each weighing `V (n·l) 4 (v·h) / (n·h)`.
pub fn sheen_albedo(n_v: f32, roughness: f32) -> f32 {
    let alpha = roughness.max(MIN_ROUGHNESS).powi(2);
    let v = Vec3::new((1.0 - n_v * n_v).max(0.0).sqrt(), 0.0, n_v);
    let mut sum = 0.0;
    for i in 0..SAMPLES {
        let (u, w) = (
            (i as f32 + 0.5) / SAMPLES as f32,
            i.reverse_bits() as f32 * 2.0f32.powi(-32),
        );
        let sin = w.max(1e-12).powf(alpha / (2.0 * alpha + 1.0)).min(1.0);
        let cos = (1.0 - sin * sin).sqrt();
        let phi = 2.0 * std::f32::consts::PI * u;
        let h = Vec3::new(sin * phi.cos(), sin * phi.sin(), cos);
        let v_h = v.dot(h);
        let l = 2.0 * v_h * h - v;
        if l.z > 0.0 && cos > 0.0 && v_h > 0.0 {
            sum += sheen_visibility(l.z, n_v, roughness) * l.z * 4.0 * v_h / cos;
        }
    }
    sum / SAMPLES as f32
}

/// [`sheen_albedo`] on the split-sum table's grid (prefilter.rs): row `j` is roughness
/// `(j + 0.5) / LUT_SIZE`, column `i` is `n·v = (i + 0.5) / LUT_SIZE`; at most 1, which it
/// exceeds at grazing angles and low roughness (1.46 at n·v 1/64, roughness 0.05), where
/// the visibility term is clamped rather than fitted: the base it scales by `1 - E` never
/// turns negative. Computed once per process.
pub fn sheen_albedo_lut() -> &'static [f32] {
    static LUT: OnceLock<Vec<f32>> = OnceLock::new();
    LUT.get_or_init(|| {
        let at = |k: u32| (k as f32 + 0.5) / LUT_SIZE as f32;
        (0..LUT_SIZE)
            .flat_map(|j| (0..LUT_SIZE).map(move |i| sheen_albedo(at(i), at(j)).min(1.0)))
            .collect()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The distribution is normalised: `∫ D (n·h) dh = 1` over the hemisphere.
    #[test]
    fn the_charlie_distribution_integrates_to_one() {
        for roughness in [0.2, 0.5, 1.0] {
            let steps = 4000;
            let integral: f32 = (0..steps)
                .map(|k| {
                    let theta = (k as f32 + 0.5) / steps as f32 * std::f32::consts::FRAC_PI_2;
                    let d = charlie(roughness, theta.cos());
                    d * theta.cos()
                        * theta.sin()
                        * 2.0
                        * std::f32::consts::PI
                        * (std::f32::consts::FRAC_PI_2 / steps as f32)
                })
                .sum();
            assert!(
                (integral - 1.0).abs() < 1e-3,
                "roughness {roughness}: {integral}"
            );
        }
    }

    /// The sampled albedo agrees with a brute-force integral over directions, and stays
    /// within what an energy-conserving lobe reflects.
    #[test]
    fn the_albedo_table_is_the_lobes_integral() {
        for (n_v, roughness) in [(0.9, 0.5), (0.3, 0.5), (0.6, 1.0), (0.2, 0.3)] {
            let v = Vec3::new((1.0f32 - n_v * n_v).sqrt(), 0.0, n_v);
            let (steps_t, steps_p) = (400, 400);
            let mut brute = 0.0;
            for a in 0..steps_t {
                let cos_l = (a as f32 + 0.5) / steps_t as f32;
                let sin_l = (1.0 - cos_l * cos_l).sqrt();
                for b in 0..steps_p {
                    let phi = (b as f32 + 0.5) / steps_p as f32 * 2.0 * std::f32::consts::PI;
                    let l = Vec3::new(sin_l * phi.cos(), sin_l * phi.sin(), cos_l);
                    let h = (l + v).normalize();
                    let f = charlie(roughness, h.z) * sheen_visibility(cos_l, n_v, roughness);
                    // dω = d(cos θ) dφ.
                    brute +=
                        f * cos_l / steps_t as f32 * 2.0 * std::f32::consts::PI / steps_p as f32;
                }
            }
            let sampled = sheen_albedo(n_v, roughness);
            assert!(
                (sampled - brute).abs() < 0.01 && sampled <= 1.0,
                "n.v {n_v} roughness {roughness}: sampled {sampled}, integral {brute}"
            );
        }
        let lut = sheen_albedo_lut();
        assert_eq!(lut.len(), (LUT_SIZE * LUT_SIZE) as usize);
        assert!(lut.iter().all(|e| (0.0..=1.0).contains(e)));
    }
}
