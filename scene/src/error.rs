//! Everything that can go wrong while loading or generating a scene.

use std::path::PathBuf;

/// Why a scene could not be loaded. Every variant names the file (or built-in scene) and, where
/// there is one, the mesh, primitive, material, light or camera at fault, so the message alone
/// is enough to find the problem.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    /// The file, or the folder it is in, could not be read: missing, unreadable, not a
    /// regular file, or over the size cap. (A buffer's or image's file that cannot be read is
    /// an [`SceneError::InvalidBuffer`] or [`SceneError::InvalidImage`] naming its user.)
    #[error("cannot read {file}: {source}")]
    Io {
        /// The glTF file, as given.
        file: PathBuf,
        /// The underlying error.
        #[source]
        source: rgraph_core::bounded_read::ReadError,
    },

    /// The `gltf` crate rejected the file: not JSON / GLB, or it fails glTF validation.
    #[error("{file}: not a valid glTF 2.0 file: {source}")]
    Gltf {
        /// The glTF file, as given.
        file: PathBuf,
        /// The underlying error.
        #[source]
        source: gltf::Error,
    },

    /// A `.glb` whose container (header or chunks) is inconsistent in a way the `gltf`
    /// crate does not catch itself.
    #[error("{file}: not a valid GLB file: {reason}")]
    InvalidGlb {
        /// The glTF file, as given.
        file: PathBuf,
        /// What is wrong, in words.
        reason: String,
    },

    /// The file lists an extension in `extensionsRequired` that this loader does not implement,
    /// so any rendering of it would be wrong.
    #[error(
        "{file}: requires glTF extension {extension}, which is not implemented \
         (implemented: {implemented})"
    )]
    UnsupportedRequiredExtension {
        /// The glTF file, as given.
        file: PathBuf,
        /// The extension required.
        extension: String,
        /// The extensions the loader implements, comma-separated.
        implemented: String,
    },

    /// A buffer's data is missing (its file too), unreachable or shorter than declared.
    #[error("{file}: buffer {buffer}: {reason}")]
    InvalidBuffer {
        /// The glTF file, as given.
        file: PathBuf,
        /// The buffer's index.
        buffer: usize,
        /// What is wrong, in words.
        reason: String,
    },

    /// An accessor's type, layout or bounds are inconsistent with its buffer view or its use.
    #[error("{file}: {mesh} primitive {primitive}: {attribute} accessor {accessor}: {reason}")]
    InvalidAccessor {
        /// The glTF file, as given.
        file: PathBuf,
        /// The glTF mesh, by index and name.
        mesh: String,
        /// The primitive's index in its mesh.
        primitive: usize,
        /// What the accessor holds: "POSITION", "indices", ...
        attribute: &'static str,
        /// The accessor's index.
        accessor: usize,
        /// What is wrong, in words.
        reason: String,
    },

    /// A morph target's attribute accessor is not one glTF allows: not VEC3, not one
    /// element per vertex of its primitive, or holding a value that is not finite.
    #[error(
        "{file}: {mesh} primitive {primitive}: morph target {target} {attribute} accessor \
         {accessor}: {reason}"
    )]
    InvalidMorphTarget {
        /// The glTF file, as given.
        file: PathBuf,
        /// The glTF mesh, by index and name.
        mesh: String,
        /// The primitive's index in its mesh.
        primitive: usize,
        /// The target's index in the primitive.
        target: usize,
        /// What the accessor holds: "POSITION", "NORMAL" or "TANGENT".
        attribute: &'static str,
        /// The accessor's index.
        accessor: usize,
        /// What is wrong, in words.
        reason: String,
    },

    /// A skin is not one glTF allows: no joints or too many, a joint outside the loaded
    /// scene, or an inverseBindMatrices accessor of the wrong type, count or values.
    #[error("{file}: {skin}: {reason}")]
    InvalidSkin {
        /// The glTF file, as given.
        file: PathBuf,
        /// The skin, by index and name.
        skin: String,
        /// What is wrong, naming the accessor or node where one is at fault.
        reason: String,
    },

    /// A vertex attribute holds NaN or infinity.
    #[error(
        "{file}: {mesh} primitive {primitive}: vertex {vertex} has a non-finite {attribute} \
         {value:?}"
    )]
    NonFiniteVertex {
        /// The glTF file, as given.
        file: PathBuf,
        /// The glTF mesh, by index and name.
        mesh: String,
        /// The primitive's index in its mesh.
        primitive: usize,
        /// The vertex's index in the primitive.
        vertex: usize,
        /// The attribute: "POSITION", "NORMAL", ...
        attribute: &'static str,
        /// The attribute's components.
        value: Vec<f32>,
    },

    /// An index refers past the end of the primitive's vertex array.
    #[error(
        "{file}: {mesh} primitive {primitive}: index #{position} is {index}, but there are only \
         {vertex_count} vertices"
    )]
    IndexOutOfRange {
        /// The glTF file, as given.
        file: PathBuf,
        /// The glTF mesh, by index and name.
        mesh: String,
        /// The primitive's index in its mesh.
        primitive: usize,
        /// Where the index is in the index list.
        position: usize,
        /// The index.
        index: u32,
        /// The primitive's vertices.
        vertex_count: usize,
    },

    /// A primitive's index count is not what its mode needs (e.g. TRIANGLES not a multiple of 3).
    #[error("{file}: {mesh} primitive {primitive}: {reason}")]
    InvalidPrimitive {
        /// The glTF file, as given.
        file: PathBuf,
        /// The glTF mesh, by index and name.
        mesh: String,
        /// The primitive's index in its mesh.
        primitive: usize,
        /// What is wrong, in words.
        reason: String,
    },

    /// Every placement of a mesh together is more than the scene may hold (checked before
    /// any is built).
    #[error("{file}: {mesh}: {reason}")]
    InvalidMesh {
        /// The glTF file, as given.
        file: PathBuf,
        /// The glTF mesh, by index and name.
        mesh: String,
        /// What is wrong, in words.
        reason: String,
    },

    /// A material's image could not be located or decoded.
    #[error("{file}: {image} ({slot} of {material}): {reason}")]
    InvalidImage {
        /// The glTF file, as given.
        file: PathBuf,
        /// The image, by index and name or URI.
        image: String,
        /// Which of the material's textures uses it: "base color", "emissive", ...
        slot: &'static str,
        /// The material, by index and name.
        material: String,
        /// What is wrong, in words.
        reason: String,
    },

    /// A material factor is not a finite f32.
    #[error("{file}: {material}: {reason}")]
    InvalidMaterial {
        /// The glTF file, as given.
        file: PathBuf,
        /// The material, by index and name.
        material: String,
        /// What is wrong, in words.
        reason: String,
    },

    /// A light's parameters are outside what KHR_lights_punctual allows.
    #[error("{file}: {light}: {reason}")]
    InvalidLight {
        /// The glTF file, as given.
        file: PathBuf,
        /// The light, by index and name.
        light: String,
        /// What is wrong, in words.
        reason: String,
    },

    /// A camera's parameters cannot make a projection.
    #[error("{file}: {camera}: {reason}")]
    InvalidCamera {
        /// The glTF file, as given.
        file: PathBuf,
        /// The camera, by index and name.
        camera: String,
        /// What is wrong, in words.
        reason: String,
    },

    /// A node's transform is not finite, or puts it beyond
    /// [`MAX_COORDINATE`](super::MAX_COORDINATE).
    #[error("{file}: {node}: {reason}")]
    InvalidNode {
        /// The glTF file, as given.
        file: PathBuf,
        /// The node, by index and name.
        node: String,
        /// What is wrong, in words.
        reason: String,
    },

    /// A node's EXT_mesh_gpu_instancing attribute names no accessor, or one of a type or
    /// count the extension does not allow, or holds a value that is not finite.
    #[error("{file}: {node}: EXT_mesh_gpu_instancing {attribute}: {reason}")]
    InvalidInstances {
        /// The glTF file, as given.
        file: PathBuf,
        /// The node, by index and name.
        node: String,
        /// The instance attribute: "TRANSLATION", "ROTATION", "SCALE", or "attributes" for
        /// the extension object itself.
        attribute: &'static str,
        /// What is wrong, in words.
        reason: String,
    },

    /// An animation channel or its sampler is not one glTF allows: its target, its
    /// interpolation, or its input (key times) or output (values) accessor.
    #[error("{file}: {animation} channel {channel}: {reason}")]
    InvalidAnimation {
        /// The glTF file, as given.
        file: PathBuf,
        /// The animation, by index and name.
        animation: String,
        /// The channel's index in its animation.
        channel: usize,
        /// What is wrong, naming the accessor where one is at fault.
        reason: String,
    },

    /// An animation asked for by name or index that the scene does not have.
    #[error("scene \"{scene}\" has no animation \"{given}\" (its animations: {available})")]
    UnknownAnimation {
        /// The scene, by name.
        scene: String,
        /// The name or index asked for.
        given: String,
        /// The scene's animations, `INDEX "NAME"` comma-separated, or why there are none.
        available: String,
    },

    /// Something of the scene lies beyond [`MAX_COORDINATE`](super::MAX_COORDINATE) from the
    /// origin, or its bounds are not finite.
    #[error(
        "{scene}: {what} reaches {value:e}, beyond ±{max:e} (the largest coordinate a scene \
         may have: f64 still resolves 1/8000 unit there, and f32 camera-relative math stays \
         finite)"
    )]
    TooFar {
        /// The scene, by its spec.
        scene: String,
        /// What reaches so far: a vertex of a mesh, a light, the camera.
        what: String,
        /// Its largest coordinate magnitude.
        value: f64,
        /// The limit.
        max: f64,
    },

    /// A node is reached twice from the scene's roots: a cycle or a shared child, both of which
    /// glTF forbids (the hierarchy must be a forest).
    #[error("{file}: {node} is reached twice in the node hierarchy (cycle or shared child)")]
    NodeHierarchy {
        /// The glTF file, as given.
        file: PathBuf,
        /// The node, by index and name.
        node: String,
    },

    /// More lights than [`MAX_LIGHTS`](super::MAX_LIGHTS).
    #[error("{scene}: more than {max} lights (the most a scene may have: each is drawn as its own volume)")]
    TooManyLights {
        /// The scene, by its spec.
        scene: String,
        /// The limit.
        max: u32,
    },

    /// More meshes than [`MAX_MESHES`](super::MAX_MESHES), counted before any is built.
    #[error("{scene}: {count} meshes (glTF primitives as placed by nodes), more than {max} (the most a scene may have: each keeps 128 bytes of per-mesh data in one device binding)")]
    TooManyMeshes {
        /// The scene, by its spec.
        scene: String,
        /// The meshes it would have.
        count: u64,
        /// The limit.
        max: u32,
    },

    /// More particles than [`MAX_PARTICLES`](super::MAX_PARTICLES) over all emitters.
    #[error("{scene}: {count} particles, more than {max} (the most a scene may have: each is an instance of one draw, 32 bytes on the device)")]
    TooManyParticles {
        /// The scene, by its spec.
        scene: String,
        /// The particles over all emitters.
        count: usize,
        /// The limit.
        max: usize,
    },

    /// A particle that cannot be drawn (see [`Particle::invalid`](super::Particle::invalid)).
    #[error("{scene}: emitter \"{emitter}\" particle {index}: {reason}")]
    InvalidParticle {
        /// The scene, by its spec.
        scene: String,
        /// The emitter's name.
        emitter: String,
        /// The particle's index in its emitter.
        index: usize,
        /// What is wrong, in words.
        reason: String,
    },

    /// Nothing to draw: no triangle, point or line segment survived loading.
    #[error("{scene}: the scene contains no triangles, points or lines")]
    EmptyScene {
        /// The scene, by its spec.
        scene: String,
    },

    /// `builtin:NAME` with a NAME that is not a built-in scene.
    #[error("unknown built-in scene `{name}`; available: {available}")]
    UnknownBuiltin {
        /// The name asked for.
        name: String,
        /// The built-in scenes' names, comma-separated.
        available: String,
    },

    /// A `builtin:NAME?key=value` parameter that the scene does not take or cannot parse.
    #[error("builtin:{scene}: {reason}")]
    BuiltinParameter {
        /// The built-in scene's name.
        scene: String,
        /// What is wrong, in words.
        reason: String,
    },
}

/// How errors and warnings name a glTF object: its kind and index, plus its name when it has one
/// (names are optional and not unique, indices are what a glTF validator reports).
pub(crate) fn label(kind: &str, index: usize, name: Option<&str>) -> String {
    match name {
        Some(name) => format!("{kind} {index} \"{name}\""),
        None => format!("{kind} {index}"),
    }
}
