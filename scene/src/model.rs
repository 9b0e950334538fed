//! The scene itself: what a renderer needs to draw one view, as plain data. Loading is
//! `Scene::load` (scene/mod.rs), from glTF files (gltf_loader/) or built-in scenes
//! (procedural/), both through `SceneBuilder`.

use super::{
    Aabb, Animation, Camera, Deformation, Environment, Light, Material, Mesh, NodeTree,
    ParticleEmitter, PointsLines, Skin, TextureImage,
};

/// Everything a renderer needs to draw one view of a scene.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    /// The spec it was loaded from: the file path or `builtin:NAME[?params]`.
    pub name: String,
    /// Each with at least one triangle; at least one, except for a glTF scene that lists no
    /// nodes, which loads empty with a warning (the frame shows only the background), and
    /// a scene of points and lines only.
    pub meshes: Vec<Mesh>,
    /// glTF points and lines (modes POINTS, LINES, LINE_LOOP, LINE_STRIP), each with at
    /// least one point or segment, placed at rest where the file's nodes place them, and
    /// in a frame where its pose's `points_lines` do (the animations move them with their
    /// nodes). Built-in scenes have none.
    pub points_lines: Vec<PointsLines>,
    /// Indexed by `Mesh::material`.
    pub materials: Vec<Material>,
    /// Indexed by `TextureRef::image`.
    pub textures: Vec<TextureImage>,
    /// Punctual lights, world space; at most [`MAX_LIGHTS`](crate::MAX_LIGHTS).
    pub lights: Vec<Light>,
    /// Linear RGB ambient radiance multiplied with base color (glTF has none: zero for files).
    pub ambient: [f32; 3],
    /// Image-based lighting, added to the ambient term and the lights: the default
    /// lighting of files without lights (see [`Lighting`](super::Lighting)); built-in scenes have none.
    pub environment: Option<Environment>,
    /// Particle emitters, drawn by the `particles` pass after lighting; glTF files have
    /// none, `builtin:smoke` has two, an engine adds its own. At most
    /// [`MAX_PARTICLES`](super::MAX_PARTICLES) particles over all of them, each valid
    /// ([`Particle::invalid`](super::Particle::invalid)): [`Scene::check_particles`].
    pub emitters: Vec<ParticleEmitter>,
    /// The file's first camera in scene order, else [`Camera::framing`] of the bounds.
    pub camera: Camera,
    /// World-space bounds of all vertices: exact at rest, and grown to hold the meshes'
    /// and the points' and lines' object-space boxes wherever [`Scene::animations`] move
    /// them (sampled at and between their key times).
    pub bounds: Aabb,
    /// The node hierarchy placing the meshes and the skins' joints, which the animations
    /// move: a glTF file's, when it has animations or skins; empty otherwise.
    pub nodes: NodeTree,
    /// A glTF file's skins (none for built-in scenes): joints of [`Scene::nodes`] that
    /// deform the meshes bound to them.
    pub skins: Vec<Skin>,
    /// The meshes that skins or morph targets deform, in the order of their meshes, each
    /// mesh at most once; [`Mesh::vertices`] hold their rest shape. Empty for scenes
    /// without (built-in ones), whose renders pay nothing for deformation.
    pub deformations: Vec<Deformation>,
    /// A glTF file's animations of node translations, rotations, scales and morph
    /// weights (none for built-in scenes); [`Scene::animated_pose`] samples one into a
    /// frame's [`Pose`](crate::Pose).
    pub animations: Vec<Animation>,
    /// Things the loader ignored or changed, each naming the object concerned.
    pub warnings: Vec<String>,
}
