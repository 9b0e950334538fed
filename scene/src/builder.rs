//! Assembly shared by the glTF loader and the built-in scenes.

use glam::DVec3;

use super::{
    Aabb, BoundingSphere, Camera, Light, Material, Mesh, ParticleEmitter, Scene, SceneError,
    TextureImage, MAX_COORDINATE,
};

/// A scene under construction: loaders push parts, [`SceneBuilder::finish`] derives the rest.
pub(crate) struct SceneBuilder {
    pub name: String,
    pub meshes: Vec<Mesh>,
    pub materials: Vec<Material>,
    pub textures: Vec<TextureImage>,
    pub lights: Vec<Light>,
    pub ambient: [f32; 3],
    pub camera: Option<Camera>,
    pub emitters: Vec<ParticleEmitter>,
    pub warnings: Vec<String>,
    /// Whether a scene without triangles is what the source asked for (a glTF scene listing
    /// no nodes) rather than a sign that everything was skipped; see [`SceneBuilder::finish`].
    pub allow_empty: bool,
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
            emitters: Vec::new(),
            warnings: Vec::new(),
            allow_empty: false,
        }
    }

    /// Appends a material and returns its index.
    pub fn add_material(&mut self, material: Material) -> usize {
        self.materials.push(material);
        self.materials.len() - 1
    }

    /// Drops meshes without triangles, computes the bounds and, when no camera was set, frames
    /// the vertices' sphere around their center with [`Camera::framing`]. Fails with [`SceneError::EmptyScene`] when no triangle is
    /// left, unless [`SceneBuilder::allow_empty`] is set (the loader has warned): then the
    /// bounds are the origin and the frame shows only the background. Fails with
    /// [`SceneError::TooFar`] when the bounds, a light or the camera lie beyond
    /// ±[`MAX_COORDINATE`] (or are not finite), which would otherwise render an empty frame.
    pub fn finish(mut self) -> Result<Scene, SceneError> {
        self.meshes.retain(|m| m.triangle_count() > 0);
        let bounds = self
            .meshes
            .iter()
            .filter_map(Mesh::world_bounds)
            .reduce(|a, b| a.union(&b));
        let bounds = match bounds {
            Some(bounds) => bounds,
            None if self.allow_empty => Aabb::from_points([DVec3::ZERO]).expect("one point"),
            None => return Err(SceneError::EmptyScene { scene: self.name }),
        };
        self.check_extent("the geometry", bounds.largest_coordinate())?;
        for light in &self.lights {
            let what = format!("the position of {}", light.name);
            self.check_extent(&what, light.position.abs().max_element())?;
        }
        if let Some(camera) = &self.camera {
            let what = format!("the position of the camera ({})", camera.name);
            self.check_extent(&what, camera.position.abs().max_element())?;
        }
        let scene = Scene {
            camera: self.camera.unwrap_or_else(|| {
                let points = self.meshes.iter().flat_map(Mesh::world_positions);
                Camera::framing(&BoundingSphere::around(bounds.center(), points))
            }),
            name: self.name,
            meshes: self.meshes,
            materials: self.materials,
            textures: self.textures,
            lights: self.lights,
            ambient: self.ambient,
            environment: None,
            emitters: self.emitters,
            bounds,
            warnings: self.warnings,
        };
        scene.check_particles()?;
        Ok(scene)
    }

    /// Fails when `value` (a largest coordinate magnitude) is beyond [`MAX_COORDINATE`] or NaN.
    fn check_extent(&self, what: &str, value: f64) -> Result<(), SceneError> {
        if value <= MAX_COORDINATE {
            return Ok(());
        }
        Err(SceneError::TooFar {
            scene: self.name.clone(),
            what: what.to_owned(),
            value,
            max: MAX_COORDINATE,
        })
    }
}
