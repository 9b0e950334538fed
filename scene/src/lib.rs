//! The CPU-side scene model and its sources: glTF 2.0 files and built-in procedural scenes.
//!
//! A [`Scene`] is plain data ready for upload: object-space vertex arrays with f64 world
//! transforms, metallic-roughness materials, decoded RGBA8 textures, punctual lights in world
//! space, one camera, and a glTF file's animations, skins and morph targets
//! ([`Scene::animated_pose`] poses the meshes at a time). [`Scene::load`] takes either a path to a `.gltf` / `.glb` file or
//! `builtin:NAME` (see [`builtin_names`]), optionally with parameters: `builtin:lights?count=1024`.
//!
//! Nothing here touches the GPU or prints: problems that still allow rendering come back as
//! [`Scene::warnings`], problems that do not as a [`SceneError`].
//!
//! Conventions: world space is glTF's (right-handed, +Y up, metres by convention); world
//! positions and transforms are f64 so that scenes far from the origin render
//! camera-relative without losing precision; colors are linear RGB unless a field says
//! sRGB; light intensities are glTF's photometric units (candela, lux).
//!
//! ```
//! use rgraph_scene::analysis::Features;
//! use rgraph_scene::{Scene, SceneError};
//!
//! // Five spheres on a ground plane, one sun and four point lights.
//! let scene = Scene::load("builtin:spheres")?;
//! let stats = scene.stats();
//! assert_eq!((stats.meshes, stats.point_lights, stats.directional_lights), (6, 4, 1));
//! assert!(scene.warnings.is_empty());
//!
//! // What a pipeline can specialise on: the features graph-file conditions test.
//! let features = Features::of(&scene);
//! assert!(features.point_lights && !features.spot_lights && !features.particles);
//!
//! // Parameters are checked before anything is built, and errors say what is accepted.
//! let error = Scene::load("builtin:lights?count=-1").unwrap_err();
//! assert!(matches!(error, SceneError::BuiltinParameter { .. }));
//! # Ok::<(), SceneError>(())
//! ```

#![deny(missing_docs)]

pub mod analysis;
mod animation;
mod assets;
mod bounds;
mod builder;
mod camera;
mod clusters;
mod deform;
mod environment;
mod error;
mod gltf_loader;
mod light;
mod lighting;
mod material;
mod material_layers;
mod mesh;
mod mips;
mod model;
mod node_tree;
mod normals;
mod particles;
mod points_lines;
mod prefilter;
mod procedural;
mod sheen;
mod stats;
mod tangents;
mod texture;
pub mod texture_table;

use std::path::Path;

/// The math crate of the scene API (`DVec3` positions, `DMat4` transforms), so callers
/// building a [`Scene`] in code use the same version.
pub use glam;

pub use animation::{Animation, AnimationId, Channel, Interpolation, Keyframes};
pub use assets::{AssetPolicy, DEFAULT_MAX_ASSET_BYTES, DEFAULT_MAX_SCENE_BYTES};
pub use bounds::{Aabb, BoundingSphere, MAX_COORDINATE};
pub use camera::{
    Camera, DepthConvention, Projection, FRAMING_DIRECTION, FRAMING_FILL, FRAMING_YFOV,
};
pub use clusters::{cluster, Cluster, ClusteredMesh, CLUSTER_TRIANGLES};
pub use deform::{
    joints_in_object_space, Deformation, Influences, MorphTarget, MorphTargets, Pose, Reach, Skin,
    SkinWeights, MAX_JOINTS,
};
pub use environment::{
    irradiance_integral, radiance as environment_radiance, Environment, Irradiance,
};
pub use error::SceneError;
pub use light::{Light, LightKind, LightVolume, DEFAULT_CUTOFF_ILLUMINANCE, MAX_LIGHTS};
pub use lighting::{Lighting, DEFAULT_ENVIRONMENT_INTENSITY, HEADLIGHT_LUX};
pub use material::{AlphaMode, Material, TEXTURE_SLOTS};
pub use material_layers::{dielectric_f0, Clearcoat, Sheen, Specular, DEFAULT_IOR};
pub use mesh::{Mesh, Vertex, MAX_MESHES};
pub use model::Scene;
pub use node_tree::{LocalTransform, MeshPlacement, Node, NodeId, NodeTree, Trs};
pub use normals::flat_shaded;
pub use particles::{billboard_pixels, check_emitters, Particle, ParticleEmitter, MAX_PARTICLES};
pub use points_lines::{PointsLines, Topology};
pub use prefilter::{
    cube_direction, prefilter, prefiltered_cube, split_sum, split_sum_lut, CUBE_LEVELS, CUBE_SIZE,
    LUT_SIZE,
};
pub use procedural::{builtin_names, BuiltinParam, BuiltinScene, BUILTIN_PREFIX};
pub use sheen::{charlie, sheen_albedo, sheen_albedo_lut, sheen_visibility};
pub use stats::SceneStats;
pub use tangents::generate_tangents;
pub use texture::{FilterMode, Sampler, TextureImage, TextureRef, WrapMode};

impl Scene {
    /// Loads `builtin:NAME[?key=value&...]` or a `.gltf` / `.glb` file path, with the
    /// default [`AssetPolicy`].
    pub fn load(spec: &str) -> Result<Scene, SceneError> {
        Scene::load_with(spec, &AssetPolicy::default())
    }

    /// [`Scene::load`], with a glTF file's reads limited by `policy`.
    pub fn load_with(spec: &str, policy: &AssetPolicy) -> Result<Scene, SceneError> {
        match spec.strip_prefix(BUILTIN_PREFIX) {
            Some(builtin) => Scene::builtin(builtin),
            None => Scene::from_gltf_with(Path::new(spec), policy),
        }
    }

    /// Loads a glTF 2.0 file (`.gltf` with embedded or external buffers, or `.glb`), with
    /// the default [`AssetPolicy`].
    pub fn from_gltf(path: &Path) -> Result<Scene, SceneError> {
        Scene::from_gltf_with(path, &AssetPolicy::default())
    }

    /// [`Scene::from_gltf`], reading only what `policy` allows.
    pub fn from_gltf_with(path: &Path, policy: &AssetPolicy) -> Result<Scene, SceneError> {
        gltf_loader::load(path, policy)
    }

    /// Generates a built-in scene from `NAME[?key=value&...]` (without the `builtin:` prefix).
    pub fn builtin(spec: &str) -> Result<Scene, SceneError> {
        procedural::build(spec)
    }

    /// Fails when the emitters hold more than [`MAX_PARTICLES`] particles or a particle
    /// that cannot be drawn, naming the emitter and the particle. Loading checks it; an
    /// engine that adds emitters to a loaded scene calls it before handing the scene over
    /// (frame inputs' emitters are checked by `Host::set_frame`).
    pub fn check_particles(&self) -> Result<(), SceneError> {
        particles::check_emitters(&self.name, &self.emitters)
    }

    /// The particles of every emitter, in emitter order.
    pub fn particles(&self) -> impl Iterator<Item = &Particle> {
        self.emitters.iter().flat_map(|e| e.particles.iter())
    }

    /// What the scene holds, counted: meshes, triangles, lights by kind, materials by
    /// feature.
    pub fn stats(&self) -> SceneStats {
        SceneStats::of(self)
    }
}
