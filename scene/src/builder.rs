//! Assembly shared by the glTF loader and the built-in scenes.

use glam::DVec3;

use super::animation::{swept_bounds, Animation};
use super::node_tree::{MeshPlacement, NodeTree};
use super::{
    Aabb, BoundingSphere, Camera, Deformation, Light, Material, Mesh, ParticleEmitter, PointsLines,
    Scene, SceneError, Skin, TextureImage, MAX_COORDINATE,
};

/// A scene under construction: loaders push parts, [`SceneBuilder::finish`] derives the rest.
pub(crate) struct SceneBuilder {
    pub name: String,
    pub meshes: Vec<Mesh>,
    pub points_lines: Vec<PointsLines>,
    pub materials: Vec<Material>,
    pub textures: Vec<TextureImage>,
    pub lights: Vec<Light>,
    pub ambient: [f32; 3],
    pub camera: Option<Camera>,
    pub emitters: Vec<ParticleEmitter>,
    pub warnings: Vec<String>,
    /// The nodes placing the meshes and the points and lines, with one placement per
    /// mesh and per points-and-lines primitive pushed, when `animations` move them or
    /// `skins` hang on them (else empty).
    pub nodes: NodeTree,
    pub skins: Vec<Skin>,
    /// By index into `meshes` as pushed; `finish` renumbers them as it drops meshes.
    pub deformations: Vec<Deformation>,
    pub animations: Vec<Animation>,
    /// Whether a scene without triangles is what the source asked for (a glTF scene listing
    /// no nodes) rather than a sign that everything was skipped; see [`SceneBuilder::finish`].
    pub allow_empty: bool,
}

impl SceneBuilder {
    pub fn new(name: impl Into<String>) -> SceneBuilder {
        SceneBuilder {
            name: name.into(),
            meshes: Vec::new(),
            points_lines: Vec::new(),
            materials: Vec::new(),
            textures: Vec::new(),
            lights: Vec::new(),
            ambient: [0.0; 3],
            camera: None,
            emitters: Vec::new(),
            warnings: Vec::new(),
            nodes: NodeTree::default(),
            skins: Vec::new(),
            deformations: Vec::new(),
            animations: Vec::new(),
            allow_empty: false,
        }
    }

    /// Appends a material and returns its index.
    pub fn add_material(&mut self, material: Material) -> usize {
        self.materials.push(material);
        self.materials.len() - 1
    }

    /// Drops meshes without triangles and points and lines without a point or segment
    /// (and their placements in `nodes`), computes the
    /// bounds (swept over the animations' poses, see [`swept_bounds`]) and, when no camera
    /// was set, frames the vertices' sphere around their center with [`Camera::framing`],
    /// grown to hold the swept bounds; the points and lines at rest count as still
    /// geometry (the swept bounds hold them where the animations take them). Fails with
    /// [`SceneError::EmptyScene`] when no triangle, point or segment is left, unless [`SceneBuilder::allow_empty`] is set (the loader has warned): then the
    /// bounds are the origin and the frame shows only the background. Fails with
    /// [`SceneError::TooFar`] when the bounds, a light or the camera lie beyond
    /// ±[`MAX_COORDINATE`] (or are not finite), which would otherwise render an empty frame.
    pub fn finish(mut self) -> Result<Scene, SceneError> {
        // Each mesh's index once those without triangles are dropped.
        let kept: Vec<Option<usize>> = (self.meshes.iter())
            .scan(0, |next, m| {
                let kept = (m.triangle_count() > 0).then_some(*next);
                *next += usize::from(kept.is_some());
                Some(kept)
            })
            .collect();
        self.deformations
            .retain_mut(|d| kept[d.mesh].map(|mesh| d.mesh = mesh).is_some());
        retain_placed(&mut self.meshes, &mut self.nodes.meshes, |m| {
            m.triangle_count() > 0
        });
        retain_placed(&mut self.points_lines, &mut self.nodes.points_lines, |p| {
            p.count() > 0
        });
        // A deformed mesh is where its deformation puts it, not where its rest vertices
        // are (a skinned mesh's node transform is ignored): the swept bounds below hold
        // it, from the rest pose on.
        let mut deformed = vec![false; self.meshes.len()];
        for d in &self.deformations {
            deformed[d.mesh] = true;
        }
        let still: Vec<usize> = (0..self.meshes.len()).filter(|&i| !deformed[i]).collect();
        let still_bounds = (still.iter())
            .filter_map(|&i| self.meshes[i].world_bounds())
            .chain(
                self.points_lines
                    .iter()
                    .filter_map(PointsLines::world_bounds),
            )
            .reduce(|a, b| a.union(&b));
        let bounds = match still_bounds {
            Some(bounds) => bounds,
            None if self.allow_empty || !self.deformations.is_empty() => {
                Aabb::from_points([DVec3::ZERO]).expect("one point")
            }
            None => return Err(SceneError::EmptyScene { scene: self.name }),
        };
        check_extent(&self.name, "the geometry", bounds.largest_coordinate())?;
        for light in &self.lights {
            let what = format!("the position of {}", light.name);
            check_extent(&self.name, &what, light.position.abs().max_element())?;
        }
        if let Some(camera) = &self.camera {
            let what = format!("the position of the camera ({})", camera.name);
            check_extent(&self.name, &what, camera.position.abs().max_element())?;
        }
        let framed = self.camera.is_none();
        let mut scene = Scene {
            camera: self.camera.unwrap_or_else(|| {
                let points = still.iter().flat_map(|&i| self.meshes[i].world_positions());
                let points =
                    points.chain(self.points_lines.iter().flat_map(|p| p.world_positions()));
                Camera::framing(&BoundingSphere::around(bounds.center(), points))
            }),
            name: self.name,
            meshes: self.meshes,
            points_lines: self.points_lines,
            materials: self.materials,
            textures: self.textures,
            lights: self.lights,
            ambient: self.ambient,
            environment: None,
            emitters: self.emitters,
            bounds,
            nodes: self.nodes,
            skins: self.skins,
            deformations: self.deformations,
            animations: self.animations,
            warnings: self.warnings,
        };
        if let Some(swept) = swept_bounds(&scene) {
            scene.bounds = still_bounds.map_or(swept, |b| b.union(&swept));
            let what = "the geometry, as the animations and deformations move it";
            check_extent(&scene.name, what, scene.bounds.largest_coordinate())?;
            if framed {
                let points = still
                    .iter()
                    .flat_map(|&i| scene.meshes[i].world_positions());
                let strokes = scene.points_lines.iter().flat_map(|p| p.world_positions());
                let points = points.chain(strokes).chain(swept.corners());
                let sphere = BoundingSphere::around(scene.bounds.center(), points);
                scene.camera = Camera::framing(&sphere);
            }
        }
        scene.check_particles()?;
        Ok(scene)
    }
}

/// Keeps the `items` that `keep` accepts and, when `placements` has one per item (it is
/// empty otherwise), their placements.
fn retain_placed<T>(
    items: &mut Vec<T>,
    placements: &mut Vec<MeshPlacement>,
    keep: impl Fn(&T) -> bool,
) {
    if placements.is_empty() {
        items.retain(keep);
        return;
    }
    let placed = std::mem::take(items)
        .into_iter()
        .zip(std::mem::take(placements));
    (*items, *placements) = placed.filter(|(item, _)| keep(item)).unzip();
}

/// Fails when `value` (a largest coordinate magnitude of `what` in scene `scene`) is beyond
/// [`MAX_COORDINATE`] or NaN.
fn check_extent(scene: &str, what: &str, value: f64) -> Result<(), SceneError> {
    if value <= MAX_COORDINATE {
        return Ok(());
    }
    Err(SceneError::TooFar {
        scene: scene.to_owned(),
        what: what.to_owned(),
        value,
        max: MAX_COORDINATE,
    })
}
