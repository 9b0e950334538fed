//! Assembly shared by the glTF loader and the built-in scenes.

use super::{Camera, Light, Material, Mesh, Scene, SceneError, TextureImage};

/// A scene under construction: loaders push parts, [`SceneBuilder::finish`] derives the rest.
pub(crate) struct SceneBuilder {
    pub name: String,
    pub meshes: Vec<Mesh>,
    pub materials: Vec<Material>,
    pub textures: Vec<TextureImage>,
    pub lights: Vec<Light>,
    pub ambient: [f32; 3],
    pub camera: Option<Camera>,
    pub warnings: Vec<String>,
}

impl SceneBuilder {
    pub fn new(name: impl Into<String>) -> SceneBuilder {
        SceneBuilder {
            name: name.into(),
            meshes: Vec::new(),
            materials: Vec::new(),
            textures: Vec::new(),
            lights: Vec::new(),
            ambient: [0.0; 3],
            camera: None,
            warnings: Vec::new(),
        }
    }

    /// Appends a material and returns its index.
    pub fn add_material(&mut self, material: Material) -> usize {
        self.materials.push(material);
        self.materials.len() - 1
    }

    /// Drops meshes without triangles, computes the bounds and, when no camera was set, frames
    /// them with [`Camera::framing`]. Fails with [`SceneError::EmptyScene`] when no triangle is
    /// left, since nothing downstream can render or frame an empty scene.
    pub fn finish(mut self) -> Result<Scene, SceneError> {
        self.meshes.retain(|m| m.triangle_count() > 0);
        let bounds = self
            .meshes
            .iter()
            .filter_map(Mesh::world_bounds)
            .reduce(|a, b| a.union(&b));
        let Some(bounds) = bounds else {
            return Err(SceneError::EmptyScene { scene: self.name });
        };
        Ok(Scene {
            camera: self.camera.unwrap_or_else(|| Camera::framing(&bounds)),
            name: self.name,
            meshes: self.meshes,
            materials: self.materials,
            textures: self.textures,
            lights: self.lights,
            ambient: self.ambient,
            bounds,
            warnings: self.warnings,
        })
    }
}
