//! KHR_materials_pbrSpecularGlossiness, converted to metallic-roughness at load, so every
//! pipeline keeps its one material model.
//!
//! The conversion is the one published with the extension (Khronos's
//! "convert-between-workflows" example, which Babylon.js's and three.js's converters
//! follow), in linear light, with dielectrics' reflectance F0 = 0.04 and the perceived
//! brightness `sqrt(0.299 r² + 0.587 g² + 0.114 b²)`:
//!
//! - metallic is 0 where the specular is darker than a dielectric's; elsewhere it is the
//!   root of the quadratic that makes a metal-rough material's diffuse and specular
//!   brightness match the spec-gloss ones ([`solve_metallic`]);
//! - the base colour blends the diffuse colour (rescaled for the light the specular takes
//!   and the metal share) with the specular colour less its dielectric part, by
//!   `metallic²`, clamped to 0..=1;
//! - roughness is `1 - glossiness`; alpha is the diffuse alpha.
//!
//! It is exact where the two models coincide: a dielectric (specular 0.04 grey: metallic 0,
//! base colour the diffuse colour) and a metal (diffuse black: metallic 1, base colour the
//! specular colour). Between them it is the published approximation: spec-gloss can say
//! more (a coloured dielectric specular, a lit diffuse under a metal's specular) than
//! metal-rough can.
//!
//! Factors alone convert as above. Textures are baked at load into a base colour texture
//! (sRGB) and a metallicRoughness texture (linear: green roughness, blue metallic), the
//! factors folded in and the converted material's own factors 1, texel by texel:
//!
//! - When the diffuse and specularGlossiness textures sample the same texture coordinates
//!   (one UV set, one KHR_texture_transform), or only one of them exists, both outputs are
//!   baked on one grid, the larger width and the larger height of the two, each input
//!   resampled to it bilinearly (texel centres aligned, in its sRGB encoding): exact at the
//!   grid's texel centres but for 8-bit rounding. Between them the renderer interpolates
//!   converted values instead of converting interpolated ones (the conversion is not
//!   linear), and mips average converted values.
//! - When they sample different coordinates, no texel of one is a texel of the other: the
//!   base colour is baked at the diffuse texture's size with the specularGlossiness
//!   texture replaced by its mean, the metallicRoughness at the specularGlossiness
//!   texture's size with the diffuse texture replaced by its mean (means in linear light).
//!   A warning says so.
//!
//! Each output is sampled as its source is (the diffuse texture's sampler and coordinates
//! for the base colour, the specularGlossiness one's for metallicRoughness; the other's
//! where its own source is missing). Their memory is taken from the scene's budget before
//! anything is built (`reserve`, two textures of the grid's size, an upper bound of
//! either case); the decoded inputs, freed after baking, are bounded by their headers as
//! every image is.

use gltf::material::PbrSpecularGlossiness;

use super::material::{reference, Pbr, Sampled};
use super::{factors, reserve, Loader};
use crate::mips::{linear_to_srgb, srgb_to_linear};
use crate::texture_table::resampled;
use crate::{SceneError, TextureImage};

/// The reflectance at normal incidence both models give dielectrics.
const DIELECTRIC_F0: f64 = 0.04;

/// Keeps the conversion's divisions finite where metallic is 0 or 1 (where the term
/// divided has no weight).
const EPSILON: f64 = 1e-6;

/// One point of a metallic-roughness material, linear.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct MetalRough {
    pub base_color: [f64; 4],
    pub metallic: f64,
    pub roughness: f64,
}

/// Converts one point of a spec-gloss material: linear diffuse RGBA, linear specular RGB and
/// glossiness, each within 0..=1 (see the module documentation).
pub(super) fn convert(diffuse: [f64; 4], specular: [f64; 3], glossiness: f64) -> MetalRough {
    let one_minus_specular = 1.0 - specular.into_iter().fold(0.0, f64::max);
    let metallic = solve_metallic(
        brightness([diffuse[0], diffuse[1], diffuse[2]]),
        brightness(specular),
        one_minus_specular,
    );
    let diffuse_scale = one_minus_specular / (1.0 - DIELECTRIC_F0) / (1.0 - metallic).max(EPSILON);
    let [r, g, b] = std::array::from_fn(|i| {
        let from_diffuse = diffuse[i] * diffuse_scale;
        let from_specular =
            (specular[i] - DIELECTRIC_F0 * (1.0 - metallic)) / metallic.max(EPSILON);
        let weight = metallic * metallic;
        (from_diffuse * (1.0 - weight) + from_specular * weight).clamp(0.0, 1.0)
    });
    MetalRough {
        base_color: [r, g, b, diffuse[3]],
        metallic,
        roughness: 1.0 - glossiness,
    }
}

/// Perceived brightness of a linear colour.
fn brightness([r, g, b]: [f64; 3]) -> f64 {
    (0.299 * r * r + 0.587 * g * g + 0.114 * b * b).sqrt()
}

/// The metallic of a metal-rough material whose brightness matches `diffuse` and `specular`
/// (perceived brightness) with `one_minus_specular` = 1 - the specular's largest component.
/// A metal-rough material reflects `F0 (1 - m) + base m` specularly and diffuses
/// `base (1 - F0)(1 - m)`; eliminating the base colour leaves `F0 m² + b m + c = 0` with
/// the `b` and `c` below, whose larger root is taken. Specular darker than a dielectric's
/// is no metal at all.
fn solve_metallic(diffuse: f64, specular: f64, one_minus_specular: f64) -> f64 {
    if specular < DIELECTRIC_F0 {
        return 0.0;
    }
    let a = DIELECTRIC_F0;
    let b = diffuse * one_minus_specular / (1.0 - DIELECTRIC_F0) + specular - 2.0 * DIELECTRIC_F0;
    let c = DIELECTRIC_F0 - specular;
    // c <= 0 here, so the discriminant is at least b² (the max guards rounding only).
    let discriminant = (b * b - 4.0 * a * c).max(0.0);
    ((-b + discriminant.sqrt()) / (2.0 * a)).clamp(0.0, 1.0)
}

/// What a bake reads at each texel: a texture's texels (at the bake's size) or one value
/// everywhere; linear RGBA with its factor applied (RGB stored sRGB, alpha linear, as
/// both of the extension's textures store them).
enum Input {
    Texels {
        image: TextureImage,
        factor: [f64; 4],
    },
    Uniform([f64; 4]),
}

impl Input {
    fn at(&self, texel: usize) -> [f64; 4] {
        match self {
            Input::Uniform(value) => *value,
            Input::Texels { image, factor } => {
                let t = &image.rgba8[texel * 4..texel * 4 + 4];
                [
                    srgb_to_linear(t[0]) * factor[0],
                    srgb_to_linear(t[1]) * factor[1],
                    srgb_to_linear(t[2]) * factor[2],
                    f64::from(t[3]) / 255.0 * factor[3],
                ]
            }
        }
    }

    /// The mean value, in linear light.
    fn mean(&self) -> [f64; 4] {
        match self {
            Input::Uniform(value) => *value,
            Input::Texels { image, .. } => {
                let texels = image.width as usize * image.height as usize;
                let sum = (0..texels)
                    .map(|i| self.at(i))
                    .fold([0.0; 4], |sum, v| std::array::from_fn(|c| sum[c] + v[c]));
                sum.map(|s| s / texels as f64)
            }
        }
    }

    /// The texels' size, for a texture.
    fn size(&self) -> Option<(u32, u32)> {
        match self {
            Input::Texels { image, .. } => Some((image.width, image.height)),
            Input::Uniform(_) => None,
        }
    }

    /// This input at `width` x `height`.
    fn resampled(self, width: u32, height: u32) -> Input {
        match self {
            Input::Texels { image, factor } => Input::Texels {
                image: resampled(&image, width, height),
                factor,
            },
            uniform => uniform,
        }
    }
}

/// Converts `width` x `height` texels (inputs of that size): the base colour (sRGB, alpha
/// linear) and metallicRoughness (linear; red, unused, is 255) as RGBA8.
fn bake(width: u32, height: u32, diffuse: &Input, specular: &Input) -> [Vec<u8>; 2] {
    let texels = width as usize * height as usize;
    let unorm = |v: f64| (v * 255.0).round().clamp(0.0, 255.0) as u8;
    let mut base = Vec::with_capacity(texels * 4);
    let mut metal_rough = Vec::with_capacity(texels * 4);
    for texel in 0..texels {
        let d = diffuse.at(texel);
        let [sr, sg, sb, gloss] = specular.at(texel);
        let converted = convert(d, [sr, sg, sb], gloss);
        let [r, g, b, a] = converted.base_color;
        base.extend([
            linear_to_srgb(r),
            linear_to_srgb(g),
            linear_to_srgb(b),
            unorm(a),
        ]);
        metal_rough.extend([
            255,
            unorm(converted.roughness),
            unorm(converted.metallic),
            255,
        ]);
    }
    [base, metal_rough]
}

impl Loader<'_> {
    /// The metallic-roughness parameters of spec-gloss material `name` (see the module
    /// documentation). Factors outside 0..=1 are clamped with a warning, as core factors
    /// are.
    pub(super) fn spec_gloss(
        &mut self,
        spec_gloss: &PbrSpecularGlossiness,
        name: &str,
    ) -> Result<Pbr, SceneError> {
        let (file, warnings) = (self.file, &mut self.builder.warnings);
        let mut check = |field, values: &[f32]| {
            factors::checked(file, name, field, values, 0.0..=1.0, warnings)
        };
        let diffuse = check("diffuseFactor", &spec_gloss.diffuse_factor())?;
        let specular = check("specularFactor", &spec_gloss.specular_factor())?;
        let glossiness = check("glossinessFactor", &[spec_gloss.glossiness_factor()])?[0];
        let diffuse: [f64; 4] = std::array::from_fn(|i| f64::from(diffuse[i]));
        let specular: [f64; 4] = [
            f64::from(specular[0]),
            f64::from(specular[1]),
            f64::from(specular[2]),
            f64::from(glossiness),
        ];
        let diffuse_texture = spec_gloss.diffuse_texture();
        let diffuse_texture =
            self.sampled(diffuse_texture.as_ref().map(reference), "diffuse", name);
        let specular_texture = spec_gloss.specular_glossiness_texture();
        let specular_texture = self.sampled(
            specular_texture.as_ref().map(reference),
            "specularGlossiness",
            name,
        );
        if diffuse_texture.is_none() && specular_texture.is_none() {
            let converted = convert(
                diffuse,
                [specular[0], specular[1], specular[2]],
                specular[3],
            );
            return Ok(Pbr {
                base_color_factor: converted.base_color.map(|c| c as f32),
                base_color_texture: None,
                metallic_factor: converted.metallic as f32,
                roughness_factor: converted.roughness as f32,
                metallic_roughness_texture: None,
                from_spec_gloss: true,
            });
        }
        let diffuse_input = self.input(diffuse_texture.as_ref(), diffuse, "diffuse", name)?;
        let specular_input = self.input(
            specular_texture.as_ref(),
            specular,
            "specularGlossiness",
            name,
        )?;
        let shared = match (&diffuse_texture, &specular_texture) {
            (Some(d), Some(s)) => d.same_uvs(s),
            _ => true,
        };
        // Each output with its size.
        let (base, metal_rough) = match shared {
            true => {
                let (width, height) = [diffuse_input.size(), specular_input.size()]
                    .into_iter()
                    .flatten()
                    .fold((1, 1), |(w, h), (iw, ih)| (w.max(iw), h.max(ih)));
                let diffuse_input = diffuse_input.resampled(width, height);
                let specular_input = specular_input.resampled(width, height);
                let [base, metal_rough] = bake(width, height, &diffuse_input, &specular_input);
                ((base, (width, height)), (metal_rough, (width, height)))
            }
            // Both are textures here; each bake's other output is dropped.
            false => {
                self.builder.warnings.push(format!(
                    "{name}: KHR_materials_pbrSpecularGlossiness: the diffuse and \
                     specularGlossiness textures sample different texture coordinates, so \
                     each is converted with the other's mean value"
                ));
                let (bw, bh) = diffuse_input.size().unwrap_or((1, 1));
                let (mw, mh) = specular_input.size().unwrap_or((1, 1));
                let specular_mean = Input::Uniform(specular_input.mean());
                let diffuse_mean = Input::Uniform(diffuse_input.mean());
                let [base, _] = bake(bw, bh, &diffuse_input, &specular_mean);
                let [_, metal_rough] = bake(mw, mh, &diffuse_mean, &specular_input);
                ((base, (bw, bh)), (metal_rough, (mw, mh)))
            }
        };
        let base_sampling = diffuse_texture.as_ref().or(specular_texture.as_ref());
        let metal_rough_sampling = specular_texture.as_ref().or(diffuse_texture.as_ref());
        let base = self.baked(name, "base color", base, true);
        let metal_rough = self.baked(name, "metallicRoughness", metal_rough, false);
        Ok(Pbr {
            base_color_factor: [1.0; 4],
            base_color_texture: base_sampling.map(|s| s.with_image(base)),
            metallic_factor: 1.0,
            roughness_factor: 1.0,
            metallic_roughness_texture: metal_rough_sampling.map(|s| s.with_image(metal_rough)),
            from_spec_gloss: true,
        })
    }

    /// The bake input of one of the extension's textures: its decoded texels, else
    /// `factor` everywhere.
    fn input(
        &mut self,
        texture: Option<&Sampled>,
        factor: [f64; 4],
        slot: &'static str,
        material: &str,
    ) -> Result<Input, SceneError> {
        let Some(texture) = texture else {
            return Ok(Input::Uniform(factor));
        };
        let decoded = self.decode(texture.image, slot, material)?;
        Ok(Input::Texels {
            image: TextureImage {
                name: self.image_name(texture.image),
                width: decoded.width(),
                height: decoded.height(),
                rgba8: decoded.into_raw(),
                srgb: true,
            },
            factor,
        })
    }

    /// Adds a baked texture to the scene; returns its index.
    fn baked(
        &mut self,
        material: &str,
        slot: &str,
        (rgba8, (width, height)): (Vec<u8>, (u32, u32)),
        srgb: bool,
    ) -> usize {
        self.builder.textures.push(TextureImage {
            name: format!("{material} {slot} (converted from specular-glossiness)"),
            width,
            height,
            rgba8,
            srgb,
        });
        self.builder.textures.len() - 1
    }

    /// Takes from the budget what converting spec-gloss `material` (named `name`) bakes:
    /// two textures of the larger width and height of its diffuse and specularGlossiness
    /// images (read from their headers), which bounds what either case of the module
    /// documentation keeps.
    pub(super) fn reserve_spec_gloss(
        &mut self,
        material: &gltf::Material,
        name: &str,
    ) -> Result<(), SceneError> {
        let Some(spec_gloss) = material.pbr_specular_glossiness() else {
            return Ok(());
        };
        let sources = [
            (spec_gloss.diffuse_texture(), "diffuse"),
            (
                spec_gloss.specular_glossiness_texture(),
                "specularGlossiness",
            ),
        ];
        let mut grid: Option<(u32, u32)> = None;
        for (texture, slot) in sources {
            let Some(texture) = texture else {
                continue;
            };
            let (width, height) =
                self.image_size(texture.texture().source().index(), slot, name)?;
            let (w, h) = grid.unwrap_or((1, 1));
            grid = Some((w.max(width), h.max(height)));
        }
        let Some((width, height)) = grid else {
            return Ok(());
        };
        let why = format!(
            "baking its specular-glossiness textures as metallic-roughness (two of \
             {width}x{height})"
        );
        self.budget
            .take(2 * reserve::texture_bytes(width, height), &why)
            .map_err(|reason| SceneError::InvalidMaterial {
                file: self.file.to_owned(),
                material: name.to_owned(),
                reason,
            })
    }
}
