//! glTF materials and samplers to [`Material`]s.

use gltf::material::AlphaMode as GltfAlphaMode;
use gltf::texture::{MagFilter, MinFilter, WrappingMode};

use super::{factors, Loader};
use crate::scene::error::label;
use crate::scene::{AlphaMode, FilterMode, Material, Sampler, SceneError, TextureRef, WrapMode};

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
        let name = material.index().map_or_else(
            || "default material".to_owned(),
            |i| label("material", i, material.name()),
        );
        let pbr = material.pbr_metallic_roughness();
        let (file, warnings) = (self.file, &mut self.builder.warnings);
        let mut check = |field, values: &[f32], range| {
            factors::checked(file, &name, field, values, range, warnings)
        };
        let (unit, positive) = (0.0..=1.0, 0.0..=f32::MAX);
        let base_color = check("baseColorFactor", &pbr.base_color_factor(), unit.clone())?;
        let metallic = check("metallicFactor", &[pbr.metallic_factor()], unit.clone())?[0];
        let roughness = check("roughnessFactor", &[pbr.roughness_factor()], unit.clone())?[0];
        let emissive = check("emissiveFactor", &material.emissive_factor(), unit)?;
        let strength = material.emissive_strength().unwrap_or(1.0);
        let strength = check("emissiveStrength", &[strength], positive.clone())?[0];
        let cutoff = material.alpha_cutoff().unwrap_or(DEFAULT_ALPHA_CUTOFF);
        let cutoff = check("alphaCutoff", &[cutoff], positive)?[0];
        let alpha_mode = match material.alpha_mode() {
            GltfAlphaMode::Opaque => AlphaMode::Opaque,
            GltfAlphaMode::Mask => AlphaMode::Mask { cutoff },
            GltfAlphaMode::Blend => {
                self.builder.warnings.push(format!(
                    "{name}: alphaMode BLEND is not supported (a G-buffer holds one surface per \
                     sample); rendered as OPAQUE"
                ));
                AlphaMode::Opaque
            }
        };
        let ignored: Vec<&str> = [
            ("normal", material.normal_texture().is_some()),
            ("occlusion", material.occlusion_texture().is_some()),
            (
                "metallicRoughness",
                pbr.metallic_roughness_texture().is_some(),
            ),
            ("emissive", material.emissive_texture().is_some()),
        ]
        .into_iter()
        .filter_map(|(kind, present)| present.then_some(kind))
        .collect();
        if !ignored.is_empty() {
            self.builder.warnings.push(format!(
                "{name}: {} texture(s) ignored; only base color textures are implemented",
                ignored.join(", ")
            ));
        }
        let base_color_texture = match pbr.base_color_texture() {
            Some(info) if info.tex_coord() != 0 => {
                self.builder.warnings.push(format!(
                    "{name}: base color texture uses TEXCOORD_{}, only TEXCOORD_0 is loaded; \
                     texture ignored",
                    info.tex_coord()
                ));
                None
            }
            Some(info) => {
                let texture = info.texture();
                Some(TextureRef {
                    image: self.base_color_image(texture.source().index(), &name)?,
                    sampler: sampler(&texture.sampler()),
                })
            }
            None => None,
        };
        Ok(Material {
            base_color_factor: [base_color[0], base_color[1], base_color[2], base_color[3]],
            base_color_texture,
            metallic_factor: metallic,
            roughness_factor: roughness,
            emissive_factor: [emissive[0], emissive[1], emissive[2]],
            emissive_strength: strength,
            alpha_mode,
            double_sided: material.double_sided(),
            unlit: material.unlit(),
            name,
        })
    }
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
