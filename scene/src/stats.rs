//! Counts that characterize a scene, for reports and scene analysis.

use std::fmt;

use super::light::LightKind;
use super::material::AlphaMode;
use super::Scene;

/// What a scene holds. Material counts overlap: one material can be emissive and textured.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SceneStats {
    /// Meshes (glTF primitives).
    pub meshes: usize,
    /// Triangles over all meshes.
    pub triangles: usize,
    /// Vertices over all meshes.
    pub vertices: usize,
    /// Point lights.
    pub point_lights: usize,
    /// Spot lights.
    pub spot_lights: usize,
    /// Directional lights.
    pub directional_lights: usize,
    /// Image-based lighting (the default lighting of files without lights).
    pub environment: bool,
    /// Materials.
    pub materials: usize,
    /// Materials with KHR_materials_unlit.
    pub unlit_materials: usize,
    /// Materials that emit light (a non-zero emissive factor).
    pub emissive_materials: usize,
    /// Materials with alpha mode MASK.
    pub mask_materials: usize,
    /// Materials with alpha mode BLEND.
    pub blend_materials: usize,
    /// Materials with a base-color texture.
    pub textured_materials: usize,
    /// Double-sided materials.
    pub double_sided_materials: usize,
    /// Decoded texture images.
    pub textures: usize,
}

impl SceneStats {
    /// The bytes of vertices and indices the meshes hold (a [`Vertex`](super::Vertex) each
    /// and a `u32` per triangle corner), as a renderer uploads them.
    pub fn geometry_bytes(&self) -> u64 {
        let vertex = std::mem::size_of::<super::Vertex>() as u64;
        self.vertices as u64 * vertex + 3 * self.triangles as u64 * 4
    }

    /// Counts what `scene` holds.
    pub fn of(scene: &Scene) -> SceneStats {
        let lights =
            |kind: fn(&LightKind) -> bool| scene.lights.iter().filter(|l| kind(&l.kind)).count();
        let materials =
            |has: fn(&super::Material) -> bool| scene.materials.iter().filter(|m| has(m)).count();
        SceneStats {
            meshes: scene.meshes.len(),
            triangles: scene.meshes.iter().map(|m| m.triangle_count()).sum(),
            vertices: scene.meshes.iter().map(|m| m.vertices.len()).sum(),
            point_lights: lights(|k| matches!(k, LightKind::Point)),
            spot_lights: lights(|k| matches!(k, LightKind::Spot { .. })),
            directional_lights: lights(|k| matches!(k, LightKind::Directional)),
            environment: scene.environment.is_some(),
            materials: scene.materials.len(),
            unlit_materials: materials(|m| m.unlit),
            emissive_materials: materials(|m| m.is_emissive()),
            mask_materials: materials(|m| matches!(m.alpha_mode, AlphaMode::Mask { .. })),
            blend_materials: materials(|m| m.alpha_mode == AlphaMode::Blend),
            textured_materials: materials(|m| m.base_color_texture.is_some()),
            double_sided_materials: materials(|m| m.double_sided),
            textures: scene.textures.len(),
        }
    }
}

impl fmt::Display for SceneStats {
    /// One line, e.g. `12 meshes, 20480 triangles, 9000 vertices; lights: 4 point, 0 spot,
    /// 1 directional; 6 materials (0 unlit, 1 emissive, 0 mask, 0 blend, 2 textured, 0
    /// double-sided), 2 textures`; `, environment` follows the lights of a scene with one.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} meshes, {} triangles, {} vertices; lights: {} point, {} spot, {} directional{}; \
             {} materials ({} unlit, {} emissive, {} mask, {} blend, {} textured, {} \
             double-sided), {} textures",
            self.meshes,
            self.triangles,
            self.vertices,
            self.point_lights,
            self.spot_lights,
            self.directional_lights,
            if self.environment {
                ", environment"
            } else {
                ""
            },
            self.materials,
            self.unlit_materials,
            self.emissive_materials,
            self.mask_materials,
            self.blend_materials,
            self.textured_materials,
            self.double_sided_materials,
            self.textures
        )
    }
}
