//! glTF materials and samplers to [`Material`]s.

use gltf::material::AlphaMode as GltfAlphaMode;
use gltf::texture::{MagFilter, MinFilter, WrappingMode};

use super::{factors, texture_transform, Loader};
use crate::error::label;
use crate::{AlphaMode, FilterMode, Material, Sampler, SceneError, TextureRef, WrapMode};

/// glTF's default alpha cutoff for MASK.
const DEFAULT_ALPHA_CUTOFF: f32 = 0.5;

impl Loader<'_> {
    /// The scene material index for a glTF material, converting it on first use.
    pub(super) fn material(&mut self, material: &gltf::Material) -> Result<usize, SceneError> {
        if let Some(&index) = self.materials.get(&material.index()) {
            return Ok(index);
        }
        let converted = self.convert_material(material)?;
        let index = self.builder.add_material(converted);
        self.materials.insert(material.index(), index);
        Ok(index)
    }

    fn convert_material(&mut self, material: &gltf::Material) -> Result<Material, SceneError> {
        let name = name(material);
        let pbr = match material.pbr_specular_glossiness() {
            Some(spec_gloss) => self.spec_gloss(&spec_gloss, &name)?,
            None => self.metal_rough(&material.pbr_metallic_roughness(), &name)?,
        };
        let layers = self.layers(material, &pbr, &name)?;
        let (file, warnings) = (self.file, &mut self.builder.warnings);
        let mut check = |field, values: &[f32], range| {
            factors::checked(file, &name, field, values, range, warnings)
        };
        let (unit, positive) = (0.0..=1.0, 0.0..=f32::MAX);
        let emissive = check("emissiveFactor", &material.emissive_factor(), unit)?;
        let strength = material.emissive_strength().unwrap_or(1.0);
        let strength = check("emissiveStrength", &[strength], positive.clone())?[0];
        let cutoff = material.alpha_cutoff().unwrap_or(DEFAULT_ALPHA_CUTOFF);
        let cutoff = check("alphaCutoff", &[cutoff], positive)?[0];
        let alpha_mode = match material.alpha_mode() {
            GltfAlphaMode::Opaque => AlphaMode::Opaque,
            GltfAlphaMode::Mask => AlphaMode::Mask { cutoff },
            GltfAlphaMode::Blend => AlphaMode::Blend,
        };
        let emissive_texture = self.texture(
            material.emissive_texture().as_ref().map(reference),
            "emissive",
            true,
            &name,
        )?;
        let occlusion = material.occlusion_texture();
        let occlusion_texture = self.texture(
            occlusion.as_ref().map(|o| {
                let transform = o.extension_value(TRANSFORM);
                (o.texture(), o.tex_coord(), transform)
            }),
            "occlusion",
            false,
            &name,
        )?;
        let normal = material.normal_texture();
        let normal_texture = self.texture(
            normal.as_ref().map(|n| {
                let transform = n.extension_value(TRANSFORM);
                (n.texture(), n.tex_coord(), transform)
            }),
            "normal",
            false,
            &name,
        )?;
        Ok(Material {
            base_color_factor: pbr.base_color_factor,
            base_color_texture: pbr.base_color_texture,
            metallic_factor: pbr.metallic_factor,
            roughness_factor: pbr.roughness_factor,
            metallic_roughness_texture: pbr.metallic_roughness_texture,
            normal_texture,
            normal_scale: normal.map_or(1.0, |n| n.scale()),
            occlusion_texture,
            occlusion_strength: occlusion.map_or(1.0, |o| o.strength()),
            emissive_factor: [emissive[0], emissive[1], emissive[2]],
            emissive_texture,
            emissive_strength: strength,
            alpha_mode,
            double_sided: material.double_sided(),
            unlit: material.unlit(),
            ior: layers.ior,
            specular: layers.specular,
            clearcoat: layers.clearcoat,
            sheen: layers.sheen,
            name,
        })
    }

    /// The core model's parameters: pbrMetallicRoughness's factors and textures.
    fn metal_rough(
        &mut self,
        pbr: &gltf::material::PbrMetallicRoughness,
        name: &str,
    ) -> Result<Pbr, SceneError> {
        let (file, warnings) = (self.file, &mut self.builder.warnings);
        let mut check = |field, values: &[f32]| {
            factors::checked(file, name, field, values, 0.0..=1.0, warnings)
        };
        let base_color = check("baseColorFactor", &pbr.base_color_factor())?;
        let metallic = check("metallicFactor", &[pbr.metallic_factor()])?[0];
        let roughness = check("roughnessFactor", &[pbr.roughness_factor()])?[0];
        let base_color_texture = self.texture(
            pbr.base_color_texture().as_ref().map(reference),
            "base color",
            true,
            name,
        )?;
        let metallic_roughness_texture = self.texture(
            pbr.metallic_roughness_texture().as_ref().map(reference),
            "metallicRoughness",
            false,
            name,
        )?;
        Ok(Pbr {
            base_color_factor: [base_color[0], base_color[1], base_color[2], base_color[3]],
            base_color_texture,
            metallic_factor: metallic,
            roughness_factor: roughness,
            metallic_roughness_texture,
            from_spec_gloss: false,
        })
    }

    /// `texture` with its texture coordinate set and its KHR_texture_transform object, as
    /// the material's `slot` texture, its image decoded as `srgb` color or linear data;
    /// `None` without one, or as [`Loader::sampled`] leaves it out.
    pub(super) fn texture(
        &mut self,
        texture: Option<(gltf::Texture, u32, Option<&serde_json::Value>)>,
        slot: &'static str,
        srgb: bool,
        material: &str,
    ) -> Result<Option<TextureRef>, SceneError> {
        let Some(sampled) = self.sampled(texture, slot, material) else {
            return Ok(None);
        };
        let image = self.image(sampled.image, srgb, slot, material)?;
        Ok(Some(sampled.with_image(image)))
    }

    /// How `texture`, with its texture coordinate set and its KHR_texture_transform object,
    /// is sampled as the material's `slot` texture; `None` without one, or (with a warning)
    /// when it uses another set of texture coordinates than TEXCOORD_0 and TEXCOORD_1, the
    /// ones loaded. A transform that cannot be read is ignored with a warning.
    pub(super) fn sampled(
        &mut self,
        texture: Option<(gltf::Texture, u32, Option<&serde_json::Value>)>,
        slot: &'static str,
        material: &str,
    ) -> Option<Sampled> {
        let (texture, mut tex_coord, transform) = texture?;
        let mut uv_transform = TextureRef::IDENTITY_UV;
        match transform.map(texture_transform::read) {
            None => {}
            Some(Ok(transform)) => {
                uv_transform = transform.matrix;
                tex_coord = transform.tex_coord.unwrap_or(tex_coord);
            }
            Some(Err(reason)) => self
                .builder
                .warnings
                .push(format!("{material}: {slot} texture: {reason}; ignored")),
        }
        if tex_coord > 1 {
            self.builder.warnings.push(format!(
                "{material}: {slot} texture uses TEXCOORD_{tex_coord}, only TEXCOORD_0 and \
                 TEXCOORD_1 are loaded; texture ignored"
            ));
            return None;
        }
        Some(Sampled {
            image: texture.source().index(),
            sampler: sampler(&texture.sampler()),
            tex_coord,
            uv_transform,
        })
    }
}

/// A material's metallic-roughness parameters: pbrMetallicRoughness's, or those converted
/// from KHR_materials_pbrSpecularGlossiness (see `spec_gloss`).
pub(super) struct Pbr {
    pub base_color_factor: [f32; 4],
    pub base_color_texture: Option<TextureRef>,
    pub metallic_factor: f32,
    pub roughness_factor: f32,
    pub metallic_roughness_texture: Option<TextureRef>,
    /// Converted from KHR_materials_pbrSpecularGlossiness.
    pub from_spec_gloss: bool,
}

/// A texture reference as the material samples it: a glTF image and how it is sampled.
pub(super) struct Sampled {
    /// The glTF image's index.
    pub image: usize,
    pub sampler: Sampler,
    pub tex_coord: u32,
    pub uv_transform: [[f32; 2]; 3],
}

impl Sampled {
    /// The reference to scene texture `image`, sampled so.
    pub(super) fn with_image(&self, image: usize) -> TextureRef {
        TextureRef {
            image,
            sampler: self.sampler,
            tex_coord: self.tex_coord,
            uv_transform: self.uv_transform,
        }
    }

    /// Whether `other` is sampled at the same texture coordinates (set and transform).
    pub(super) fn same_uvs(&self, other: &Sampled) -> bool {
        self.tex_coord == other.tex_coord && self.uv_transform == other.uv_transform
    }
}

/// A material as messages name it.
pub(super) fn name(material: &gltf::Material) -> String {
    material.index().map_or_else(
        || "default material".to_owned(),
        |i| label("material", i, material.name()),
    )
}

/// The images `material`'s core textures name, each with its slot and whether it is
/// decoded as sRGB color (as `convert_material` decodes them): what it may ask the scene to
/// hold, with its extensions' (`material_layers::images`).
pub(super) fn images(material: &gltf::Material) -> Vec<(usize, &'static str, bool)> {
    let pbr = material.pbr_metallic_roughness();
    let image = |texture: gltf::Texture| texture.source().index();
    // A specular-glossiness material's diffuse and specularGlossiness images are baked
    // into textures of its own (counted by `reserve`); its metallic-roughness fallback is
    // not used.
    let metal_rough = material.pbr_specular_glossiness().is_none();
    [
        (
            pbr.base_color_texture()
                .filter(|_| metal_rough)
                .map(|t| image(t.texture())),
            "base color",
            true,
        ),
        (
            pbr.metallic_roughness_texture()
                .filter(|_| metal_rough)
                .map(|t| image(t.texture())),
            "metallicRoughness",
            false,
        ),
        (
            material.emissive_texture().map(|t| image(t.texture())),
            "emissive",
            true,
        ),
        (
            material.occlusion_texture().map(|t| image(t.texture())),
            "occlusion",
            false,
        ),
        (
            material.normal_texture().map(|t| image(t.texture())),
            "normal",
            false,
        ),
    ]
    .into_iter()
    .filter_map(|(index, slot, srgb)| Some((index?, slot, srgb)))
    .collect()
}

/// The extension that transforms a texture reference's UVs.
const TRANSFORM: &str = "KHR_texture_transform";

/// A texture reference's texture, texture coordinate set and transform extension.
pub(super) fn reference<'a>(
    info: &'a gltf::texture::Info<'a>,
) -> (gltf::Texture<'a>, u32, Option<&'a serde_json::Value>) {
    (
        info.texture(),
        info.tex_coord(),
        info.extension_value(TRANSFORM),
    )
}

/// A glTF sampler; missing filters get [`Sampler::default`]'s.
fn sampler(sampler: &gltf::texture::Sampler) -> Sampler {
    let wrap = |mode| match mode {
        WrappingMode::Repeat => WrapMode::Repeat,
        WrappingMode::MirroredRepeat => WrapMode::MirroredRepeat,
        WrappingMode::ClampToEdge => WrapMode::ClampToEdge,
    };
    let default = Sampler::default();
    let (min_filter, mipmap_filter) = match sampler.min_filter() {
        None => (default.min_filter, default.mipmap_filter),
        Some(MinFilter::Nearest) => (FilterMode::Nearest, None),
        Some(MinFilter::Linear) => (FilterMode::Linear, None),
        Some(MinFilter::NearestMipmapNearest) => (FilterMode::Nearest, Some(FilterMode::Nearest)),
        Some(MinFilter::LinearMipmapNearest) => (FilterMode::Linear, Some(FilterMode::Nearest)),
        Some(MinFilter::NearestMipmapLinear) => (FilterMode::Nearest, Some(FilterMode::Linear)),
        Some(MinFilter::LinearMipmapLinear) => (FilterMode::Linear, Some(FilterMode::Linear)),
    };
    Sampler {
        wrap_u: wrap(sampler.wrap_s()),
        wrap_v: wrap(sampler.wrap_t()),
        mag_filter: match sampler.mag_filter() {
            None => default.mag_filter,
            Some(MagFilter::Nearest) => FilterMode::Nearest,
            Some(MagFilter::Linear) => FilterMode::Linear,
        },
        min_filter,
        mipmap_filter,
    }
}
