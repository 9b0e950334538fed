//! Shader variants: which of a shader's feature-gated code paths a scene needs.
//!
//! The G-buffer, light, forward and transparent shaders gate the code of scene features behind WGSL
//! `override` bool constants (`override SPOT_LIGHTS: bool = true;`). Their pipelines
//! set each constant to whether the scene uses the feature, so the driver compiles out
//! what the scene lacks; the defaults (all true) are the general shader. A gated path is
//! one a scene without the feature never takes, or takes with no effect (a light that
//! emits nothing adds exactly zero, an absent texture is white, an absent emission is
//! zero), so the variant renders the scene bit-identically to the general shader
//! (tests/specialise_variants.rs checks it).
//!
//! Alpha MASK is not a gate: masked materials already draw through a pipeline (and, in
//! the G-buffer pass, an entry point) of their own, built only when a mesh uses one. The
//! other deferred shaders (edge, resolve, tone mapping, debug views) gate nothing.

use std::fmt;

use rgraph_core::file::LoadedGraph;
use rgraph_core::Plan;

use rgraph_scene::analysis::Features;
use rgraph_scene::Scene;

/// A scene feature whose code a shader can compile out.
#[derive(Copy, Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Gate {
    /// Directional lights' shading (without any, the loop over them is compiled out).
    DirectionalLights,
    /// Point lights' shading.
    PointLights,
    /// Spot lights' shading (the cone falloff).
    SpotLights,
    /// Sampling the base-color texture (without one a material's texture is white).
    Textures,
    /// Sampling the emissive texture (without one, or without emission, it is white).
    EmissiveTextures,
    /// Sampling the metallicRoughness texture (without one it is white).
    MetalRoughTextures,
    /// Perturbing normals by the normal texture (without one the normal is unchanged).
    NormalTextures,
    /// Sampling the occlusion texture (without one, occlusion is 1).
    OcclusionTextures,
    /// Flipping back faces' normals (without double-sided materials back faces are
    /// culled).
    DoubleSided,
    /// Adding material emission (zero for materials that do not emit).
    Emissive,
    /// Image-based lighting (zero irradiance and intensity without an environment).
    Environment,
    /// Reading alpha MASK materials' base colour texels in a visibility raster (without
    /// such a material every masked texel is white).
    MaskTextures,
    /// KHR_materials_ior and _specular: a dielectric F0 and specular weight of the
    /// material's (without them, the core model's 0.04 and 1).
    Specular,
    /// KHR_materials_clearcoat's coat (without it, no coat).
    Clearcoat,
    /// KHR_materials_sheen's sheen (without it, no sheen).
    Sheen,
}

impl Gate {
    /// The feature's name, as [`Features::names`] spells it.
    pub fn name(self) -> &'static str {
        match self {
            Gate::DirectionalLights => "directional_lights",
            Gate::PointLights => "point_lights",
            Gate::SpotLights => "spot_lights",
            Gate::Textures => "textures",
            Gate::EmissiveTextures => "emissive_textures",
            Gate::MetalRoughTextures => "metal_rough_textures",
            Gate::NormalTextures => "normal_textures",
            Gate::OcclusionTextures => "occlusion_textures",
            Gate::DoubleSided => "double_sided",
            Gate::Emissive => "emissive",
            Gate::Environment => "environment",
            Gate::MaskTextures => "mask_textures",
            Gate::Specular => "specular",
            Gate::Clearcoat => "clearcoat",
            Gate::Sheen => "sheen",
        }
    }

    /// The WGSL `override` that gates the feature's code.
    pub fn constant(self) -> &'static str {
        match self {
            Gate::DirectionalLights => "DIRECTIONAL_LIGHTS",
            Gate::PointLights => "POINT_LIGHTS",
            Gate::SpotLights => "SPOT_LIGHTS",
            Gate::Textures => "TEXTURES",
            Gate::EmissiveTextures => "EMISSIVE_TEXTURES",
            Gate::MetalRoughTextures => "METAL_ROUGH_TEXTURES",
            Gate::NormalTextures => "NORMAL_TEXTURES",
            Gate::OcclusionTextures => "OCCLUSION_TEXTURES",
            Gate::DoubleSided => "DOUBLE_SIDED",
            Gate::Emissive => "EMISSIVE",
            Gate::Environment => "ENVIRONMENT",
            Gate::MaskTextures => "MASK_TEXTURES",
            Gate::Specular => "SPECULAR",
            Gate::Clearcoat => "CLEARCOAT",
            Gate::Sheen => "SHEEN",
        }
    }

    /// Whether `features` use it.
    pub fn used_by(self, features: &Features) -> bool {
        match self {
            Gate::DirectionalLights => features.directional_lights,
            Gate::PointLights => features.point_lights,
            Gate::SpotLights => features.spot_lights,
            Gate::Textures => features.textures,
            Gate::EmissiveTextures => features.emissive_textures,
            Gate::MetalRoughTextures => features.metal_rough_textures,
            Gate::NormalTextures => features.normal_textures,
            Gate::OcclusionTextures => features.occlusion_textures,
            Gate::DoubleSided => features.double_sided,
            Gate::Emissive => features.emissive,
            Gate::Environment => features.environment,
            Gate::MaskTextures => features.mask_textures,
            Gate::Specular => features.specular,
            Gate::Clearcoat => features.clearcoat,
            Gate::Sheen => features.sheen,
        }
    }
}

/// The shaders with gated code.
#[derive(Copy, Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum GatedShader {
    /// gbuffer.wgsl, of the `gbuffer` plugin.
    GBuffer,
    /// light.wgsl, of `light_edge` and `light_nonedge`.
    Light,
    /// light_tiled.wgsl, of `light_tiled`.
    LightTiled,
    /// light_tiled.wgsl reading a visibility buffer: it samples the material textures
    /// itself (material_table.wgsl), so the texture gates apply too.
    LightTiledVisibility,
    /// forward.wgsl, of `forward`.
    Forward,
    /// transparent.wgsl (forward.wgsl's shading, keeping alpha), of `transparent`.
    Transparent,
    /// mask_texture.wgsl, in the visibility rasters: `visibility_compute` and
    /// `visibility`.
    VisibilityRaster,
}

impl GatedShader {
    /// The shader a pass of `plugin` runs, if it has gated code.
    pub fn of_plugin(plugin: &str) -> Option<GatedShader> {
        match plugin {
            "gbuffer" => Some(GatedShader::GBuffer),
            "light_edge" | "light_nonedge" => Some(GatedShader::Light),
            "light_tiled" => Some(GatedShader::LightTiled),
            "forward" => Some(GatedShader::Forward),
            "transparent" => Some(GatedShader::Transparent),
            "visibility_compute" | "visibility" => Some(GatedShader::VisibilityRaster),
            _ => None,
        }
    }

    /// The WGSL file (in `passes/src/wgsl/`) whose gated code the variant compiles in or
    /// out.
    pub fn file(self) -> &'static str {
        match self {
            GatedShader::GBuffer => "gbuffer.wgsl",
            GatedShader::Light => "light.wgsl",
            GatedShader::LightTiled | GatedShader::LightTiledVisibility => "light_tiled.wgsl",
            GatedShader::Forward => "forward.wgsl",
            GatedShader::Transparent => "transparent.wgsl",
            GatedShader::VisibilityRaster => "mask_texture.wgsl",
        }
    }

    /// The gates the shader's code has (brdf.wgsl's light kinds and lighting.wgsl's
    /// environment in the shaders that light).
    pub fn gates(self) -> &'static [Gate] {
        use Gate::*;
        match self {
            GatedShader::GBuffer => &[
                Textures,
                EmissiveTextures,
                MetalRoughTextures,
                NormalTextures,
                OcclusionTextures,
                DoubleSided,
                Emissive,
                Specular,
                Clearcoat,
                Sheen,
            ],
            GatedShader::Light | GatedShader::LightTiled => &[
                DirectionalLights,
                PointLights,
                SpotLights,
                Environment,
                Specular,
                Clearcoat,
                Sheen,
            ],
            GatedShader::LightTiledVisibility => &[
                DirectionalLights,
                PointLights,
                SpotLights,
                Textures,
                EmissiveTextures,
                MetalRoughTextures,
                NormalTextures,
                OcclusionTextures,
                Environment,
                Specular,
                Clearcoat,
                Sheen,
            ],
            GatedShader::Forward | GatedShader::Transparent => &[
                DirectionalLights,
                PointLights,
                SpotLights,
                Textures,
                EmissiveTextures,
                MetalRoughTextures,
                NormalTextures,
                OcclusionTextures,
                DoubleSided,
                Emissive,
                Environment,
                Specular,
                Clearcoat,
                Sheen,
            ],
            GatedShader::VisibilityRaster => &[MaskTextures],
        }
    }
}

/// One shader compiled with the code of some of its gates: a pipeline-cache key part.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Variant {
    /// The shader.
    pub shader: GatedShader,
    /// The gates whose code is compiled in, in [`GatedShader::gates`] order.
    pub compiled: Vec<Gate>,
}

impl Variant {
    /// The variant for a scene with `features`.
    pub fn of(shader: GatedShader, features: &Features) -> Variant {
        Variant {
            shader,
            compiled: shader
                .gates()
                .iter()
                .copied()
                .filter(|g| g.used_by(features))
                .collect(),
        }
    }

    /// Every gate compiled in: what the shader is without specialisation.
    pub fn general(shader: GatedShader) -> Variant {
        Variant::of(shader, &Features::general())
    }

    /// Whether every gate is compiled in: the variant is the general shader.
    pub fn is_general(&self) -> bool {
        self.compiled.len() == self.shader.gates().len()
    }

    /// The pipeline-overridable constants that select it, one per gate (1 compiled in,
    /// 0 compiled out).
    pub fn constants(&self) -> Vec<(&'static str, f64)> {
        self.shader
            .gates()
            .iter()
            .map(|g| (g.constant(), f64::from(u8::from(self.compiled.contains(g)))))
            .collect()
    }

    /// The compiled-in gates by feature name: `{point_lights, spot_lights}`.
    pub fn feature_list(&self) -> String {
        let names: Vec<&str> = self.compiled.iter().map(|g| g.name()).collect();
        format!("{{{}}}", names.join(", "))
    }
}

/// `light.wgsl {point_lights, spot_lights}`.
impl fmt::Display for Variant {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} {}", self.shader.file(), self.feature_list())
    }
}

/// Which variants the deferred plugins compile (see [`crate::register_with`]).
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub enum Variants {
    /// The scene's: only the gated code its features need.
    #[default]
    Scene,
    /// The general shaders, whatever the scene: the same images, compiled for more
    /// (for checking that specialising changes no pixel, and for comparing).
    General,
}

impl Variants {
    /// The features shaders are compiled for when drawing `scene`.
    pub fn features(self, scene: &Scene) -> Features {
        match self {
            Variants::Scene => Features::of(scene),
            Variants::General => Features::general(),
        }
    }
}

/// A variant a plan builds, and the passes that use it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ShaderVariant {
    /// The variant built.
    pub variant: Variant,
    /// In plan order.
    pub passes: Vec<String>,
}

/// Which shader variants executing a plan builds for a scene with `features`, given the
/// plan's passes in order as `(pass name, plugin name)`: one per gated shader that some
/// pass runs, in order of first use. Needs no GPU (`rgraph explain` shows it).
pub fn shader_variants(features: &Features, passes: &[(&str, &str)]) -> Vec<ShaderVariant> {
    let mut variants: Vec<ShaderVariant> = Vec::new();
    for &(pass, plugin) in passes {
        let Some(shader) = GatedShader::of_plugin(plugin) else {
            continue;
        };
        match variants.iter_mut().find(|v| v.variant.shader == shader) {
            Some(used) => used.passes.push(pass.to_owned()),
            None => variants.push(ShaderVariant {
                variant: Variant::of(shader, features),
                passes: vec![pass.to_owned()],
            }),
        }
    }
    variants
}

/// [`shader_variants`] of a plan compiled from `loaded`, which knows each pass's plugin
/// (passes added in code, without one, run no gated shader).
pub fn plan_shader_variants(
    features: &Features,
    plan: &Plan,
    loaded: &LoadedGraph,
) -> Vec<ShaderVariant> {
    let passes: Vec<(&str, &str)> = plan
        .passes
        .iter()
        .filter_map(|p| Some((p.name.as_str(), loaded.plugin(&p.name)?)))
        .collect();
    shader_variants(features, &passes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_general_variant_sets_every_constant() {
        let general = Variant::general(GatedShader::Forward);
        assert!(general.is_general());
        assert!(general.constants().iter().all(|&(_, v)| v == 1.0));
        assert_eq!(general.constants().len(), 14);
    }

    #[test]
    fn a_variant_names_its_compiled_features_and_zeroes_the_rest() {
        let features = Features {
            point_lights: true,
            spot_lights: true,
            ..Features::default()
        };
        let light = Variant::of(GatedShader::Light, &features);
        assert_eq!(light.to_string(), "light.wgsl {point_lights, spot_lights}");
        assert_eq!(
            light.constants(),
            [
                ("DIRECTIONAL_LIGHTS", 0.0),
                ("POINT_LIGHTS", 1.0),
                ("SPOT_LIGHTS", 1.0),
                ("ENVIRONMENT", 0.0),
                ("SPECULAR", 0.0),
                ("CLEARCOAT", 0.0),
                ("SHEEN", 0.0)
            ]
        );
        let gbuffer = Variant::of(GatedShader::GBuffer, &features);
        assert_eq!(gbuffer.to_string(), "gbuffer.wgsl {}");
        assert!(!gbuffer.is_general());
    }

    #[test]
    fn passes_of_one_shader_share_its_variant() {
        let passes = [
            ("gbuffer", "gbuffer"),
            ("edges", "edge_stencil"),
            ("light edges", "light_edge"),
            ("light the rest", "light_nonedge"),
            ("resolve", "resolve"),
        ];
        let variants = shader_variants(&Features::general(), &passes);
        let shown: Vec<(String, Vec<String>)> = variants
            .iter()
            .map(|v| (v.variant.to_string(), v.passes.clone()))
            .collect();
        assert_eq!(
            shown,
            [
                (
                    "gbuffer.wgsl {textures, emissive_textures, metal_rough_textures, \
                     normal_textures, occlusion_textures, double_sided, emissive, specular, \
                     clearcoat, sheen}"
                        .to_owned(),
                    vec!["gbuffer".to_owned()]
                ),
                (
                    "light.wgsl {directional_lights, point_lights, spot_lights, environment, \
                     specular, clearcoat, sheen}"
                        .to_owned(),
                    vec!["light edges".to_owned(), "light the rest".to_owned()]
                ),
            ]
        );
    }
}
