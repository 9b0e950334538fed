//! The features a scene uses, under the names graph-file conditions test.

use super::DepthRange;
use crate::texture_table::{TextureTable, WEBGPU_MAX_LAYERS, WEBGPU_MAX_SIDE};
use crate::{AlphaMode, LightKind, Material, Scene};

/// Which features a scene uses. Only what can change a rendered pixel counts: materials
/// that some mesh draws with, and lights that emit something.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Features {
    /// Some point light emits.
    pub point_lights: bool,
    /// Some spot light emits.
    pub spot_lights: bool,
    /// Some directional light emits.
    pub directional_lights: bool,
    /// A nonzero ambient term.
    pub ambient: bool,
    /// Image-based lighting (the default lighting of files without lights).
    pub environment: bool,
    /// Some mesh is drawn with an unlit material (KHR_materials_unlit).
    pub unlit: bool,
    /// Some mesh is drawn with a lit material.
    pub lit: bool,
    /// Some mesh is drawn with an emissive material.
    pub emissive: bool,
    /// Some mesh is drawn with an alpha MASK material.
    pub alpha_mask: bool,
    /// Some mesh is drawn with an alpha BLEND material: the pipelines add their
    /// transparent passes under `when: "blend"`.
    pub blend: bool,
    /// Some mesh's material samples a base-color texture.
    pub textures: bool,
    /// Some mesh's emissive material samples an emissive texture.
    pub emissive_textures: bool,
    /// Some mesh's lit material samples a metallicRoughness texture.
    pub metal_rough_textures: bool,
    /// Some mesh's lit material samples a normal texture.
    pub normal_textures: bool,
    /// Some mesh's lit material samples an occlusion texture.
    pub occlusion_textures: bool,
    /// Some mesh's alpha MASK material samples a base-color texture: the visibility
    /// rasters test its cutoff on the texel's alpha, read from the scene's texture table.
    pub mask_textures: bool,
    /// The scene's textures do not fit the texture table within WebGPU's default limits
    /// ([`TextureTable::check`]): the visibility buffer cannot shade them, and pipelines
    /// take a G-buffer for these scenes.
    pub untabled_textures: bool,
    /// Some mesh is drawn with a double-sided material.
    pub double_sided: bool,
    /// Some mesh's lit material has a dielectric specular other than the core model's
    /// (KHR_materials_ior, KHR_materials_specular).
    pub specular: bool,
    /// Some mesh's lit material has a clear coat (KHR_materials_clearcoat).
    pub clearcoat: bool,
    /// Some mesh's lit material has a clear coat that bends apart from its base: the coat
    /// has a normal texture of its own, or the base has one (which bends the base only).
    /// Without one every coat's normal is its base's, and a G-buffer need not store it.
    pub clearcoat_normal: bool,
    /// Some mesh's lit material has a sheen (KHR_materials_sheen).
    pub sheen: bool,
    /// A 24-bit unorm depth buffer with standard Z resolves the geometry's depth range
    /// as finely as [`DepthRange::shallow`] asks. A reduction, like `unlit_only`: only a
    /// scene that is measured gets it.
    pub shallow_depth: bool,
    /// The scene has particles (`builtin:smoke`, or emitters an engine adds to it): the
    /// pipelines add their particle passes under `when: "particles"`.
    pub particles: bool,
    /// The scene has points or lines (glTF modes 0 to 3): the pipelines add their
    /// `points_lines` passes under `when: "points_lines"`. Their materials count for no
    /// other feature: they are drawn unlit and untextured.
    pub points_lines: bool,
    /// Some mesh is deformed by a skin or morph targets ([`Scene::deformations`]): the
    /// TAA presets' G-buffer keeps, under `when: "deformed"`, where each sample's point was
    /// in the last pose, so that its motion follows the vertices.
    pub deformed: bool,
    /// Not the scene's but the host's choice: draw a background where nothing is (the
    /// environment, a colour, or transparency: `Background`), which pipelines do with a
    /// `background` pass under this condition. [`Features::of`] and
    /// [`Features::general`] leave it unset.
    pub background: bool,
    /// Some light emits, so some light casts a shadow (directional, spot and point lights
    /// all do), and the host has not turned shadows off: the pipelines add their
    /// shadow-map pass under `when: "shadows"`, and their light passes read it. [`Features::of`]
    /// sets it from the scene alone; a host that turns shadows off unsets it.
    pub shadows: bool,
    /// Not the scene's but the host's choice: expose each frame for its metered
    /// luminance (`Exposure::Auto`), which pipelines do with an `auto_exposure` pass
    /// under this condition. [`Features::of`] and [`Features::general`] leave it unset.
    pub auto_exposure: bool,
}

impl Features {
    /// Every name [`names`](Self::names) can yield, for a graph file's `features` list.
    pub const NAMES: [&'static str; 32] = [
        "point_lights",
        "spot_lights",
        "directional_lights",
        "ambient",
        "environment",
        "no_lights",
        "unlit",
        "lit",
        "unlit_only",
        "emissive",
        "alpha_mask",
        "blend",
        "textures",
        "emissive_textures",
        "metal_rough_textures",
        "normal_textures",
        "occlusion_textures",
        "mask_textures",
        "untabled_textures",
        "double_sided",
        "specular",
        "clearcoat",
        "clearcoat_normal",
        "sheen",
        "layer_lobes",
        "shallow_depth",
        "particles",
        "points_lines",
        "deformed",
        "shadows",
        "background",
        "auto_exposure",
    ];

    /// The features `scene` uses (`background` and `auto_exposure` unset: they are the
    /// host's).
    pub fn of(scene: &Scene) -> Features {
        let drawn: Vec<&Material> = scene
            .meshes
            .iter()
            .filter_map(|m| scene.materials.get(m.material))
            .collect();
        let material = |has: fn(&Material) -> bool| drawn.iter().any(|m| has(m));
        let light =
            |kind: fn(&LightKind) -> bool| scene.lights.iter().any(|l| l.emits() && kind(&l.kind));
        Features {
            point_lights: light(|k| matches!(k, LightKind::Point)),
            spot_lights: light(|k| matches!(k, LightKind::Spot { .. })),
            directional_lights: light(|k| matches!(k, LightKind::Directional)),
            ambient: scene.ambient.iter().any(|&c| c > 0.0),
            environment: scene.environment.is_some_and(|e| e.intensity > 0.0),
            unlit: material(|m| m.unlit),
            lit: material(|m| !m.unlit),
            emissive: material(Material::is_emissive),
            alpha_mask: material(|m| matches!(m.alpha_mode, AlphaMode::Mask { .. })),
            blend: material(|m| m.alpha_mode == AlphaMode::Blend),
            textures: material(|m| m.base_color_texture.is_some()),
            emissive_textures: material(|m| m.is_emissive() && m.emissive_texture.is_some()),
            metal_rough_textures: material(|m| !m.unlit && m.metallic_roughness_texture.is_some()),
            normal_textures: material(|m| !m.unlit && m.normal_texture.is_some()),
            occlusion_textures: material(|m| !m.unlit && m.occlusion_texture.is_some()),
            mask_textures: material(|m| {
                matches!(m.alpha_mode, AlphaMode::Mask { .. }) && m.base_color_texture.is_some()
            }),
            untabled_textures: material(|m| m.texture_slots().iter().any(Option::is_some))
                && TextureTable::of(scene)
                    .check(scene, WEBGPU_MAX_LAYERS, WEBGPU_MAX_SIDE)
                    .is_err(),
            double_sided: material(|m| m.double_sided),
            specular: material(Material::has_specular),
            clearcoat: material(Material::has_clearcoat),
            clearcoat_normal: material(Material::has_clearcoat_normal),
            sheen: material(Material::has_sheen),
            // With no geometry between the planes nothing is depth-tested: the general
            // pipeline is as good as any.
            shallow_depth: DepthRange::of(scene)
                .is_some_and(|range| range.shallow(&scene.camera.projection)),
            particles: scene.particles().next().is_some(),
            points_lines: !scene.points_lines.is_empty(),
            deformed: !scene.deformations.is_empty(),
            shadows: light(|_| true),
            background: false,
            auto_exposure: false,
        }
    }

    /// A scene that uses every feature a scene can use at once: what a pipeline that
    /// knows nothing of its scene must render. Its plan is the unspecialised one. The
    /// names of absences and reductions (`no_lights`, `unlit_only`, `shallow_depth`) are
    /// not set for it, which is why
    /// pipelines drop work only under those: compiled for no features at all, a
    /// pipeline is the general one too. The one exception among scene features is `blend`: the transparent
    /// passes are added under it, so that every scene without BLEND materials keeps
    /// exactly the plan it had before they existed; compiled for no features, a
    /// pipeline draws no blended meshes (the opaque passes skip them regardless); and so is
    /// `points_lines`, for the same reason.
    pub fn general() -> Features {
        Features {
            point_lights: true,
            spot_lights: true,
            directional_lights: true,
            ambient: true,
            environment: true,
            unlit: true,
            lit: true,
            emissive: true,
            alpha_mask: true,
            blend: true,
            textures: true,
            emissive_textures: true,
            metal_rough_textures: true,
            normal_textures: true,
            occlusion_textures: true,
            mask_textures: true,
            untabled_textures: true,
            double_sided: true,
            specular: true,
            clearcoat: true,
            clearcoat_normal: true,
            sheen: true,
            shallow_depth: false,
            particles: true,
            points_lines: true,
            deformed: true,
            shadows: true,
            background: false,
            auto_exposure: false,
        }
    }

    /// No light emits and there is no ambient term or environment: lighting adds nothing.
    pub fn no_lights(&self) -> bool {
        !(self.point_lights
            || self.spot_lights
            || self.directional_lights
            || self.ambient
            || self.environment)
    }

    /// Some lit material adds a lobe of its own over its base, a clear coat or a sheen:
    /// the light pre-pass accumulates their light apart from the base's.
    pub fn layer_lobes(&self) -> bool {
        self.clearcoat || self.sheen
    }

    /// Every material drawn is unlit: nothing needs normals, material parameters or
    /// lights.
    pub fn unlit_only(&self) -> bool {
        self.unlit && !self.lit
    }

    /// The features set, by the names in [`NAMES`](Self::NAMES).
    pub fn names(&self) -> rgraph_core::Features {
        let set = [
            self.point_lights,
            self.spot_lights,
            self.directional_lights,
            self.ambient,
            self.environment,
            self.no_lights(),
            self.unlit,
            self.lit,
            self.unlit_only(),
            self.emissive,
            self.alpha_mask,
            self.blend,
            self.textures,
            self.emissive_textures,
            self.metal_rough_textures,
            self.normal_textures,
            self.occlusion_textures,
            self.mask_textures,
            self.untabled_textures,
            self.double_sided,
            self.specular,
            self.clearcoat,
            self.clearcoat_normal,
            self.sheen,
            self.layer_lobes(),
            self.shallow_depth,
            self.particles,
            self.points_lines,
            self.deformed,
            self.shadows,
            self.background,
            self.auto_exposure,
        ];
        Self::NAMES
            .iter()
            .zip(set)
            .filter(|(_, set)| *set)
            .map(|(name, _)| *name)
            .collect()
    }
}
