//! What KHR_materials_ior, KHR_materials_specular, KHR_materials_clearcoat and
//! KHR_materials_sheen add to a metallic-roughness [`Material`](crate::Material): the
//! dielectric specular's strength and colour, a clear coat over the base, and a sheen under
//! it. Each has the values its extension's absence means, so a material without them
//! shades as the core model does (`Default`).

use super::texture::TextureRef;

/// The index of refraction glTF's core dielectric assumes: F0 = 0.04.
pub const DEFAULT_IOR: f32 = 1.5;

/// KHR_materials_specular: the strength and colour of a dielectric's specular reflection.
/// Metals (metallic 1) ignore it.
#[derive(Clone, Debug, PartialEq)]
pub struct Specular {
    /// `specularFactor`, 0 (no specular: the diffuse takes all) to 1, scaling F0 and F90.
    pub factor: f32,
    /// `specularTexture`, linear, alpha channel, multiplies `factor`.
    pub texture: Option<TextureRef>,
    /// `specularColorFactor`, linear RGB, at least 0: multiplies the dielectric F0 of the
    /// index of refraction (the product is clamped to 1).
    pub color_factor: [f32; 3],
    /// `specularColorTexture`, sRGB, RGB channels, multiplies `color_factor`.
    pub color_texture: Option<TextureRef>,
}

impl Default for Specular {
    fn default() -> Specular {
        Specular {
            factor: 1.0,
            texture: None,
            color_factor: [1.0; 3],
            color_texture: None,
        }
    }
}

/// KHR_materials_clearcoat: a clear dielectric layer (index of refraction 1.5) over the
/// base, a GGX lobe with its own roughness and normal.
#[derive(Clone, Debug, PartialEq)]
pub struct Clearcoat {
    /// `clearcoatFactor`, 0 (no coat) to 1.
    pub factor: f32,
    /// `clearcoatTexture`, linear, red channel, multiplies `factor`.
    pub texture: Option<TextureRef>,
    /// `clearcoatRoughnessFactor`, perceptual roughness 0 to 1.
    pub roughness_factor: f32,
    /// `clearcoatRoughnessTexture`, linear, green channel, multiplies `roughness_factor`.
    pub roughness_texture: Option<TextureRef>,
    /// `clearcoatNormalTexture`, tangent-space normals as glTF's normalTexture; without
    /// one the coat follows the mesh's interpolated normal, not the base's normal texture.
    pub normal_texture: Option<TextureRef>,
    /// `clearcoatNormalTexture.scale`: scales the sampled normal's X and Y.
    pub normal_scale: f32,
}

impl Default for Clearcoat {
    fn default() -> Clearcoat {
        Clearcoat {
            factor: 0.0,
            texture: None,
            roughness_factor: 0.0,
            roughness_texture: None,
            normal_texture: None,
            normal_scale: 1.0,
        }
    }
}

/// KHR_materials_sheen: the back-scattering of fibres (cloth, velvet), a Charlie sheen
/// lobe over the base, which it darkens by the light the sheen takes.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Sheen {
    /// `sheenColorFactor`, linear RGB 0 to 1; black (the default) is no sheen.
    pub color_factor: [f32; 3],
    /// `sheenColorTexture`, sRGB, RGB channels, multiplies `color_factor`.
    pub color_texture: Option<TextureRef>,
    /// `sheenRoughnessFactor`, perceptual roughness 0 to 1.
    pub roughness_factor: f32,
    /// `sheenRoughnessTexture`, linear, alpha channel, multiplies `roughness_factor`.
    pub roughness_texture: Option<TextureRef>,
}

/// A dielectric's reflectance at normal incidence for index of refraction `ior` (in air):
/// `((ior - 1) / (ior + 1))²`, 0.04 for 1.5, 0 for 1 (no reflection facing the viewer) and
/// 1 for KHR_materials_ior's special value 0 (full reflection).
/// Computed in f64, so that 1.5 gives exactly the f32 0.04 the shaders' core model uses.
pub fn dielectric_f0(ior: f32) -> f32 {
    let ior = f64::from(ior);
    ((ior - 1.0) / (ior + 1.0)).powi(2) as f32
}

impl Specular {
    /// Whether it changes nothing: the core model's specular.
    pub fn is_default(&self) -> bool {
        *self == Specular::default()
    }
}

impl Clearcoat {
    /// Whether a coat shows anywhere.
    pub fn is_used(&self) -> bool {
        self.factor > 0.0
    }
}

impl Sheen {
    /// Whether a sheen shows anywhere.
    pub fn is_used(&self) -> bool {
        self.color_factor.iter().any(|&c| c > 0.0)
    }
}
