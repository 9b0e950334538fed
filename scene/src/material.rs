//! Metallic-roughness materials as the G-buffer pass consumes them.

use super::material_layers::{Clearcoat, Sheen, Specular, DEFAULT_IOR};
use super::texture::TextureRef;

/// How many textures a material may have: [`Material::texture_slots`].
pub const TEXTURE_SLOTS: usize = 12;

/// How alpha affects coverage.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum AlphaMode {
    /// Alpha is ignored: every fragment covers its sample.
    Opaque,
    /// Fragments with `alpha < cutoff` are discarded.
    Mask {
        /// The alpha threshold, glTF's `alphaCutoff` (0.5 by default).
        cutoff: f32,
    },
    /// glTF BLEND: the surface is composited over what lies behind it with its alpha
    /// (Porter and Duff's over). A G-buffer holds one surface per sample, so the opaque
    /// passes skip these meshes and the `transparent` pass draws them, lit, after
    /// lighting (passes/transparent.rs).
    Blend,
}

/// A glTF 2.0 metallic-roughness material, with the extensions this crate implements folded in.
/// Each texture is sampled with the UV set its [`TextureRef::tex_coord`] names.
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    /// The glTF material's name, for messages.
    pub name: String,
    /// Linear RGBA, multiplied with the base-color texture and the vertex color.
    pub base_color_factor: [f32; 4],
    /// sRGB texture sampled with its UV set.
    pub base_color_texture: Option<TextureRef>,
    /// Metalness, 0 (dielectric) to 1 (metal).
    pub metallic_factor: f32,
    /// Perceptual roughness, 0 (mirror) to 1.
    pub roughness_factor: f32,
    /// glTF metallicRoughnessTexture, linear, sampled with its UV set: blue multiplies
    /// `metallic_factor`, green `roughness_factor` (red is unused; glTF packs occlusion there).
    pub metallic_roughness_texture: Option<TextureRef>,
    /// glTF normalTexture, linear tangent-space normals sampled with its UV set along the
    /// vertices' tangents; its X and Y are scaled by `normal_scale`.
    pub normal_texture: Option<TextureRef>,
    /// glTF `normalTexture.scale`: scales the sampled normal's X and Y.
    pub normal_scale: f32,
    /// glTF occlusionTexture, linear, red channel, sampled with its UV set: scales ambient
    /// light only, by `1 + occlusion_strength * (red - 1)`.
    pub occlusion_texture: Option<TextureRef>,
    /// glTF `occlusionTexture.strength`, 0 (no occlusion) to 1.
    pub occlusion_strength: f32,
    /// Linear RGB emitted radiance before `emissive_strength` and the emissive texture.
    pub emissive_factor: [f32; 3],
    /// sRGB texture sampled with its UV set, multiplied with `emissive_factor`: without it
    /// the factor alone is emitted everywhere.
    pub emissive_texture: Option<TextureRef>,
    /// KHR_materials_emissive_strength multiplier (1 without the extension).
    pub emissive_strength: f32,
    /// How alpha affects coverage.
    pub alpha_mode: AlphaMode,
    /// Back faces are drawn (and lit with the flipped normal) instead of culled.
    pub double_sided: bool,
    /// KHR_materials_unlit: output is `base color`, no lighting.
    pub unlit: bool,
    /// KHR_materials_ior: the index of refraction of the dielectric part, 1.5 without the
    /// extension; 0 (the extension's special value) or at least 1.
    pub ior: f32,
    /// KHR_materials_specular.
    pub specular: Specular,
    /// KHR_materials_clearcoat.
    pub clearcoat: Clearcoat,
    /// KHR_materials_sheen.
    pub sheen: Sheen,
}

impl Material {
    /// The glTF default material (white, fully metallic and rough), used by primitives that
    /// name no material.
    pub fn gltf_default() -> Material {
        Material {
            name: "default".to_owned(),
            base_color_factor: [1.0; 4],
            base_color_texture: None,
            metallic_factor: 1.0,
            roughness_factor: 1.0,
            metallic_roughness_texture: None,
            normal_texture: None,
            normal_scale: 1.0,
            occlusion_texture: None,
            occlusion_strength: 1.0,
            emissive_factor: [0.0; 3],
            emissive_texture: None,
            emissive_strength: 1.0,
            alpha_mode: AlphaMode::Opaque,
            double_sided: false,
            unlit: false,
            ior: DEFAULT_IOR,
            specular: Specular::default(),
            clearcoat: Clearcoat::default(),
            sheen: Sheen::default(),
        }
    }

    /// Emitted radiance where the emissive texture is white: `emissive_factor *
    /// emissive_strength`.
    pub fn emission(&self) -> [f32; 3] {
        self.emissive_factor.map(|c| c * self.emissive_strength)
    }

    /// The material's textures in the shaders' slot order (material.wgsl's `slot_uv`):
    /// base color, emissive, metallicRoughness, normal, occlusion, then the extensions':
    /// specular, specular colour, clearcoat, clearcoat roughness, clearcoat normal, sheen
    /// colour, sheen roughness.
    pub fn texture_slots(&self) -> [Option<TextureRef>; TEXTURE_SLOTS] {
        [
            self.base_color_texture,
            self.emissive_texture,
            self.metallic_roughness_texture,
            self.normal_texture,
            self.occlusion_texture,
            self.specular.texture,
            self.specular.color_texture,
            self.clearcoat.texture,
            self.clearcoat.roughness_texture,
            self.clearcoat.normal_texture,
            self.sheen.color_texture,
            self.sheen.roughness_texture,
        ]
    }

    /// Whether KHR_materials_ior or KHR_materials_specular change its dielectric specular
    /// from the core model's (F0 0.04, weight 1).
    pub fn has_specular(&self) -> bool {
        !self.unlit && (self.ior != DEFAULT_IOR || !self.specular.is_default())
    }

    /// Whether a KHR_materials_clearcoat layer shows.
    pub fn has_clearcoat(&self) -> bool {
        !self.unlit && self.clearcoat.is_used()
    }

    /// Whether its clear coat shows and bends apart from its base: the coat has a normal
    /// texture, or the base has one, which does not bend the coat (glTF).
    pub fn has_clearcoat_normal(&self) -> bool {
        self.has_clearcoat()
            && (self.clearcoat.normal_texture.is_some() || self.normal_texture.is_some())
    }

    /// Whether a KHR_materials_sheen layer shows.
    pub fn has_sheen(&self) -> bool {
        !self.unlit && self.sheen.is_used()
    }

    /// The extensions among KHR_materials_ior, _specular, _clearcoat and _sheen that
    /// change how the material shades: what a renderer storing only the core model (a
    /// G-buffer) leaves out.
    pub fn layer_extensions(&self) -> Vec<&'static str> {
        let lit = !self.unlit;
        [
            (lit && self.ior != DEFAULT_IOR, "KHR_materials_ior"),
            (lit && !self.specular.is_default(), "KHR_materials_specular"),
            (self.has_clearcoat(), "KHR_materials_clearcoat"),
            (self.has_sheen(), "KHR_materials_sheen"),
        ]
        .into_iter()
        .filter_map(|(used, name)| used.then_some(name))
        .collect()
    }

    /// Whether the material emits light at all.
    pub fn is_emissive(&self) -> bool {
        self.emission().iter().any(|&c| c > 0.0)
    }
}
