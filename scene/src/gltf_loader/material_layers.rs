//! KHR_materials_ior, KHR_materials_specular, KHR_materials_clearcoat and
//! KHR_materials_sheen to a material's [`Specular`], [`Clearcoat`] and [`Sheen`]. The gltf
//! crate parses none of them (it knows ior and specular only behind features that would
//! hide them from `extension_value`), so their JSON is read here, field by field: a field
//! of the wrong type, a texture the file does not have or a factor beyond f32 is an error
//! naming the file, the material and the field; a factor outside the extension's range is
//! clamped with a warning (`factors`), as core factors are.

use serde_json::{Map, Value};

use super::material::Pbr;
use super::{factors, Loader};
use crate::{Clearcoat, SceneError, Sheen, Specular, TextureRef, DEFAULT_IOR};

pub(super) const IOR: &str = "KHR_materials_ior";
pub(super) const SPECULAR: &str = "KHR_materials_specular";
pub(super) const CLEARCOAT: &str = "KHR_materials_clearcoat";
pub(super) const SHEEN: &str = "KHR_materials_sheen";

/// The extensions' textures: extension, field, and whether the image holds sRGB colour.
/// The field names the texture in messages.
const TEXTURES: [(&str, &str, bool); 7] = [
    (SPECULAR, "specularTexture", false),
    (SPECULAR, "specularColorTexture", true),
    (CLEARCOAT, "clearcoatTexture", false),
    (CLEARCOAT, "clearcoatRoughnessTexture", false),
    (CLEARCOAT, "clearcoatNormalTexture", false),
    (SHEEN, "sheenColorTexture", true),
    (SHEEN, "sheenRoughnessTexture", false),
];

/// What the four extensions give a material.
pub(super) struct Layers {
    pub ior: f32,
    pub specular: Specular,
    pub clearcoat: Clearcoat,
    pub sheen: Sheen,
}

impl Default for Layers {
    fn default() -> Layers {
        Layers {
            ior: DEFAULT_IOR,
            specular: Specular::default(),
            clearcoat: Clearcoat::default(),
            sheen: Sheen::default(),
        }
    }
}

/// A texture reference as an extension writes it (glTF's textureInfo, or
/// normalTextureInfo with its `scale`).
struct TextureInfo<'a> {
    index: usize,
    tex_coord: u32,
    transform: Option<&'a Value>,
    scale: f32,
}

/// One extension object of a material, read with errors that name its fields.
struct Extension<'a> {
    name: &'static str,
    object: &'a Map<String, Value>,
}

impl<'a> Extension<'a> {
    /// The extension `name` of `material`, if it has one; an error if it is not an object.
    fn of(material: &'a gltf::Material, name: &'static str) -> Result<Option<Self>, String> {
        match material.extension_value(name) {
            None => Ok(None),
            Some(Value::Object(object)) => Ok(Some(Extension { name, object })),
            Some(other) => Err(format!("{name} is {other}, not a JSON object")),
        }
    }

    /// Number `field`, `default` when absent. JSON numbers beyond f32 arrive as infinity,
    /// which `factors::checked` refuses.
    fn number(&self, field: &str, default: f32) -> Result<f32, String> {
        match self.object.get(field) {
            None => Ok(default),
            Some(value) => value
                .as_f64()
                .map(|v| v as f32)
                .ok_or_else(|| format!("{}.{field} is {value}, not a number", self.name)),
        }
    }

    /// Array of three numbers `field`, `default` when absent.
    fn numbers3(&self, field: &str, default: [f32; 3]) -> Result<[f32; 3], String> {
        let Some(value) = self.object.get(field) else {
            return Ok(default);
        };
        let numbers: Option<Vec<f32>> = value
            .as_array()
            .filter(|a| a.len() == 3)
            .and_then(|a| a.iter().map(|v| v.as_f64().map(|v| v as f32)).collect());
        match numbers {
            Some(n) => Ok([n[0], n[1], n[2]]),
            None => Err(format!(
                "{}.{field} is {value}, not an array of three numbers",
                self.name
            )),
        }
    }

    /// The texture reference `field`, if present.
    fn texture(&self, field: &str) -> Result<Option<TextureInfo<'a>>, String> {
        let Some(value) = self.object.get(field) else {
            return Ok(None);
        };
        let what = |problem: &str| format!("{}.{field} {problem}", self.name);
        let Value::Object(info) = value else {
            return Err(what(&format!("is {value}, not a JSON object")));
        };
        let index = info
            .get("index")
            .and_then(Value::as_u64)
            .ok_or_else(|| what("has no texture index (a non-negative integer)"))?;
        let tex_coord = match info.get("texCoord") {
            None => 0,
            Some(v) => v
                .as_u64()
                .and_then(|v| u32::try_from(v).ok())
                .ok_or_else(|| what(&format!("texCoord is {v}, not a non-negative integer")))?,
        };
        let scale = match info.get("scale") {
            None => 1.0,
            Some(v) => v
                .as_f64()
                .map(|v| v as f32)
                .filter(|v| v.is_finite())
                .ok_or_else(|| what(&format!("scale is {v}, not a finite number")))?,
        };
        let transform = info
            .get("extensions")
            .and_then(|e| e.get("KHR_texture_transform"));
        Ok(Some(TextureInfo {
            index: usize::try_from(index).unwrap_or(usize::MAX),
            tex_coord,
            transform,
            scale,
        }))
    }
}

impl Loader<'_> {
    /// The four extensions' parameters of `material` (named `name` in messages), whose
    /// core parameters are `pbr`.
    pub(super) fn layers(
        &mut self,
        material: &gltf::Material,
        pbr: &Pbr,
        name: &str,
    ) -> Result<Layers, SceneError> {
        let mut layers = Layers::default();
        let extensions = [IOR, SPECULAR, CLEARCOAT, SHEEN]
            .map(|e| Extension::of(material, e).map_err(|r| self.invalid(name, r)));
        let [ior, specular, clearcoat, sheen] = extensions;
        let (ior, specular, clearcoat, sheen) = (ior?, specular?, clearcoat?, sheen?);
        if pbr.from_spec_gloss {
            // The extensions define themselves over metallic-roughness only: a converted
            // specular-glossiness material has its own specular already.
            for e in [&ior, &specular, &clearcoat, &sheen].into_iter().flatten() {
                self.builder.warnings.push(format!(
                    "{name}: {} is not allowed with KHR_materials_pbrSpecularGlossiness; ignored",
                    e.name
                ));
            }
            return Ok(layers);
        }
        if let Some(e) = ior {
            layers.ior = self.ior(&e, name)?;
        }
        if let Some(e) = specular {
            let factor = self.factor(&e, "specularFactor", 1.0, name)?;
            let color = e.numbers3("specularColorFactor", [1.0; 3]);
            let color = color.map_err(|r| self.invalid(name, r))?;
            let color = self.checked(name, "specularColorFactor", &color, 0.0..=f32::MAX)?;
            layers.specular = Specular {
                factor,
                texture: self.layer_texture(&e, "specularTexture", false, name)?.0,
                color_factor: [color[0], color[1], color[2]],
                color_texture: self
                    .layer_texture(&e, "specularColorTexture", true, name)?
                    .0,
            };
        }
        if let Some(e) = clearcoat {
            let (normal_texture, normal_scale) =
                self.layer_texture(&e, "clearcoatNormalTexture", false, name)?;
            layers.clearcoat = Clearcoat {
                factor: self.factor(&e, "clearcoatFactor", 0.0, name)?,
                texture: self.layer_texture(&e, "clearcoatTexture", false, name)?.0,
                roughness_factor: self.factor(&e, "clearcoatRoughnessFactor", 0.0, name)?,
                roughness_texture: self
                    .layer_texture(&e, "clearcoatRoughnessTexture", false, name)?
                    .0,
                normal_texture,
                normal_scale,
            };
        }
        if let Some(e) = sheen {
            let color = e.numbers3("sheenColorFactor", [0.0; 3]);
            let color = color.map_err(|r| self.invalid(name, r))?;
            let color = self.checked(name, "sheenColorFactor", &color, 0.0..=1.0)?;
            layers.sheen = Sheen {
                color_factor: [color[0], color[1], color[2]],
                color_texture: self.layer_texture(&e, "sheenColorTexture", true, name)?.0,
                roughness_factor: self.factor(&e, "sheenRoughnessFactor", 0.0, name)?,
                roughness_texture: self
                    .layer_texture(&e, "sheenRoughnessTexture", false, name)?
                    .0,
            };
        }
        Ok(layers)
    }

    /// KHR_materials_ior's `ior`: 0 (its special value: full reflection) or at least 1.
    /// Anything between, or below 0, is clamped to 1 with a warning.
    fn ior(&mut self, e: &Extension, name: &str) -> Result<f32, SceneError> {
        let ior = e
            .number("ior", DEFAULT_IOR)
            .map_err(|r| self.invalid(name, r))?;
        let ior = self.checked(name, "ior", &[ior], f32::MIN..=f32::MAX)?[0];
        if ior == 0.0 || ior >= 1.0 {
            return Ok(ior);
        }
        self.builder.warnings.push(format!(
            "{name}: {IOR} ior {ior} is neither 0 nor at least 1; clamped to 1"
        ));
        Ok(1.0)
    }

    /// Number `field` of `e`, `default` when absent, within 0..=1.
    fn factor(
        &mut self,
        e: &Extension,
        field: &str,
        default: f32,
        name: &str,
    ) -> Result<f32, SceneError> {
        let value = e
            .number(field, default)
            .map_err(|r| self.invalid(name, r))?;
        Ok(self.checked(name, field, &[value], 0.0..=1.0)?[0])
    }

    fn checked(
        &mut self,
        name: &str,
        field: &str,
        values: &[f32],
        range: std::ops::RangeInclusive<f32>,
    ) -> Result<Vec<f32>, SceneError> {
        factors::checked(
            self.file,
            name,
            field,
            values,
            range,
            &mut self.builder.warnings,
        )
    }

    fn invalid(&self, name: &str, reason: String) -> SceneError {
        SceneError::InvalidMaterial {
            file: self.file.to_owned(),
            material: name.to_owned(),
            reason,
        }
    }

    /// Texture `field` of extension `e` as the material's texture of that name, its image
    /// decoded as `srgb` colour or linear data, and its `scale` (1 unless a normal texture
    /// says otherwise); `None` without one.
    fn layer_texture(
        &mut self,
        e: &Extension,
        field: &'static str,
        srgb: bool,
        name: &str,
    ) -> Result<(Option<TextureRef>, f32), SceneError> {
        let Some(info) = e.texture(field).map_err(|r| self.invalid(name, r))? else {
            return Ok((None, 1.0));
        };
        let count = self.document.textures().len();
        let Some(texture) = self.document.textures().nth(info.index) else {
            return Err(self.invalid(
                name,
                format!(
                    "{}.{field} names texture {}, but the file has {count} textures",
                    e.name, info.index
                ),
            ));
        };
        let texture = self.texture(
            Some((texture, info.tex_coord, info.transform)),
            field,
            srgb,
            name,
        )?;
        Ok((texture, info.scale))
    }
}

/// The images the extensions' textures of `material` name in `document`, each with its
/// field and whether it is decoded as sRGB colour (as `Loader::layers` decodes them), for
/// `reserve`. References that cannot be read are left to `Loader::layers` to refuse.
pub(super) fn images(
    document: &gltf::Document,
    material: &gltf::Material,
) -> Vec<(usize, &'static str, bool)> {
    if material.pbr_specular_glossiness().is_some() {
        return Vec::new();
    }
    TEXTURES
        .iter()
        .filter_map(|&(extension, field, srgb)| {
            let e = Extension::of(material, extension).ok()??;
            let info = e.texture(field).ok()??;
            let texture = document.textures().nth(info.index)?;
            Some((texture.source().index(), field, srgb))
        })
        .collect()
}
