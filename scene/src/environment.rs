//! Image-based lighting from a neutral environment: the light a scene gets from everywhere
//! when its file brings no lights of its own (glTF viewers' default), as data ready for
//! upload.
//!
//! The environment is procedural ([`radiance`]): a grey studio, brighter overhead than
//! underfoot, with two broad soft boxes (a key above front left, a rim behind right) so
//! that glossy and metallic surfaces have something to reflect. It is white: it changes
//! no material's colour. Shading splits it as glTF viewers do (Karis 2013, "Real Shading
//! in Unreal Engine 4"):
//! - diffuse: the irradiance `E(n)` as nine spherical-harmonic coefficients (Ramamoorthi
//!   and Hanrahan 2001), [`Irradiance`];
//! - specular: the radiance prefiltered with the GGX lobe of each roughness in a cube
//!   map's mip levels, and the split-sum scale and bias of the BRDF in a lookup table
//!   ([`super::prefilter`]).

use std::sync::OnceLock;

use glam::Vec3;

/// Image-based lighting for a scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Environment {
    /// Scales the neutral environment's radiance (1: about 1 overhead, 0.3 underfoot).
    pub intensity: f32,
}

/// The key soft box's direction (toward it), its peak radiance above the studio's and its
/// sharpness (a cosine power); then the rim's.
const KEY: ([f32; 3], f32, f32) = ([-0.5, 0.75, 0.45], 2.5, 12.0);
const RIM: ([f32; 3], f32, f32) = ([0.6, 0.35, -0.7], 1.2, 12.0);

/// Radiance of the neutral environment (intensity 1) arriving from unit direction `d`
/// (world space, +Y up, as glTF).
pub fn radiance(d: Vec3) -> f32 {
    // Underfoot 0.3, the horizon 0.7, overhead 1.0, blended smoothly through the horizon.
    let up = d.y.clamp(-1.0, 1.0);
    let studio = if up >= 0.0 {
        0.7 + 0.3 * up
    } else {
        0.7 + 0.4 * up
    };
    let soft_box = |(toward, peak, power): ([f32; 3], f32, f32)| {
        peak * d.dot(Vec3::from(toward).normalize()).max(0.0).powf(power)
    };
    studio + soft_box(KEY) + soft_box(RIM)
}

/// The 9 real spherical-harmonic basis functions (bands 0 to 2) are these constants times
/// [`polynomials`].
const BASIS_CONSTANT: [f32; 9] = [
    0.282_095, 0.488_603, 0.488_603, 0.488_603, 1.092_548, 1.092_548, 0.315_392, 1.092_548,
    0.546_274,
];

fn polynomials(d: Vec3) -> [f32; 9] {
    let (x, y, z) = (d.x, d.y, d.z);
    [
        1.0,
        y,
        z,
        x,
        x * y,
        y * z,
        3.0 * z * z - 1.0,
        x * z,
        x * x - y * y,
    ]
}

/// Ramamoorthi and Hanrahan's convolution of each band with the clamped cosine.
const BAND_SCALE: [f32; 9] = {
    use std::f32::consts::{FRAC_PI_4, PI};
    let two_thirds = 2.0 * PI / 3.0;
    [
        PI, two_thirds, two_thirds, two_thirds, FRAC_PI_4, FRAC_PI_4, FRAC_PI_4, FRAC_PI_4,
        FRAC_PI_4,
    ]
};

/// The irradiance `E(n) = ∫ L(ω) max(n·ω, 0) dω` of the neutral environment (intensity 1)
/// as 9 spherical-harmonic coefficients, each already convolved with the clamped cosine
/// and multiplied by its basis constant, so `E(n)` is `Σ c[i] * polynomials(n)[i]`: what the
/// shaders evaluate. Within 3% of the integral in every direction (its test).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Irradiance(pub [f32; 9]);

impl Irradiance {
    /// Projects [`radiance`] on the basis by midpoint quadrature over the sphere (the
    /// integrand is smooth: 256 x 128 cells are far below the result's error). Computed
    /// once per process: every scene upload and every frame whose inputs move a light
    /// writes it into the light info.
    pub fn neutral() -> Irradiance {
        static NEUTRAL: OnceLock<Irradiance> = OnceLock::new();
        *NEUTRAL.get_or_init(Irradiance::project_neutral)
    }

    fn project_neutral() -> Irradiance {
        let mut coefficients = [0.0f64; 9];
        for (d, cell) in sphere_cells(256) {
            let l = f64::from(radiance(d)) * cell;
            for ((c, p), k) in coefficients
                .iter_mut()
                .zip(polynomials(d))
                .zip(BASIS_CONSTANT)
            {
                *c += l * f64::from(p * k);
            }
        }
        // Folding each basis function's constant into its coefficient leaves the shader a
        // polynomial in n.
        Irradiance(std::array::from_fn(|i| {
            coefficients[i] as f32 * BAND_SCALE[i] * BASIS_CONSTANT[i]
        }))
    }

    /// `E(n)` from the coefficients, as the shaders compute it.
    pub fn at(&self, n: Vec3) -> f32 {
        self.0.iter().zip(polynomials(n)).map(|(c, p)| c * p).sum()
    }
}

/// The neutral environment's irradiance `∫ L(ω) max(n·ω, 0) dω` at unit normal `n`,
/// integrated directly over `columns` x `columns / 2` cells: the reference the spherical
/// harmonics approximate (tests compare against it).
pub fn irradiance_integral(n: Vec3, columns: u32) -> f32 {
    let sum: f64 = sphere_cells(columns)
        .map(|(d, cell)| f64::from(radiance(d) * n.dot(d).max(0.0)) * cell)
        .sum();
    sum as f32
}

/// The midpoints of a latitude-longitude grid of `columns` x `columns / 2` cells over the
/// unit sphere, each with its solid angle.
fn sphere_cells(columns: u32) -> impl Iterator<Item = (Vec3, f64)> {
    use std::f64::consts::PI;
    let rows = columns / 2;
    (0..rows).flat_map(move |row| {
        let theta = (f64::from(row) + 0.5) / f64::from(rows) * PI;
        let cell = (PI / f64::from(rows)) * (2.0 * PI / f64::from(columns)) * theta.sin();
        (0..columns).map(move |column| {
            let phi = (f64::from(column) + 0.5) / f64::from(columns) * 2.0 * PI;
            let d = Vec3::new(
                (theta.sin() * phi.cos()) as f32,
                theta.cos() as f32,
                (theta.sin() * phi.sin()) as f32,
            );
            (d, cell)
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spherical_harmonics_match_the_irradiance_integral_within_3_percent() {
        let sh = Irradiance::neutral();
        let mut worst = 0.0f32;
        for i in 0..64 {
            // A spiral of directions over the whole sphere.
            let y = 1.0 - (i as f32 + 0.5) / 32.0;
            let r = (1.0 - y * y).sqrt();
            let phi = i as f32 * 2.399_963;
            let n = Vec3::new(r * phi.cos(), y, r * phi.sin());
            let expected = irradiance_integral(n, 512);
            worst = worst.max((sh.at(n) - expected).abs() / expected);
        }
        assert!(worst < 0.03, "worst relative error {worst}");
    }

    #[test]
    fn a_uniform_white_environment_would_give_pi_and_this_one_is_brighter_above() {
        let sh = Irradiance::neutral();
        assert!(sh.at(Vec3::Y) > sh.at(-Vec3::Y) * 2.0);
        assert!(sh.at(Vec3::X) > 1.0 && sh.at(Vec3::X) < 10.0);
    }
}
