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
        file: PathBuf,
        #[source]
        source: graph_core::bounded_read::ReadError,
    },

    /// The `gltf` crate rejected the file: not JSON / GLB, or it fails glTF validation.
    #[error("{file}: not a valid glTF 2.0 file: {source}")]
    Gltf {
        file: PathBuf,
        #[source]
        source: gltf::Error,
    },

    /// A `.glb` whose container (header or chunks) is inconsistent in a way the `gltf`
    /// crate does not catch itself.
    #[error("{file}: not a valid GLB file: {reason}")]
    InvalidGlb { file: PathBuf, reason: String },

    /// The file lists an extension in `extensionsRequired` that this loader does not implement,
    /// so any rendering of it would be wrong.
    #[error(
        "{file}: requires glTF extension {extension}, which is not implemented \
         (implemented: {implemented})"
    )]
    UnsupportedRequiredExtension {
        file: PathBuf,
        extension: String,
        implemented: String,
    },

    /// A buffer's data is missing (its file too), unreachable or shorter than declared.
    #[error("{file}: buffer {buffer}: {reason}")]
    InvalidBuffer {
        file: PathBuf,
        buffer: usize,
        reason: String,
    },

    /// An accessor's type, layout or bounds are inconsistent with its buffer view or its use.
    #[error("{file}: {mesh} primitive {primitive}: {attribute} accessor {accessor}: {reason}")]
    InvalidAccessor {
        file: PathBuf,
        mesh: String,
        primitive: usize,
        attribute: &'static str,
        accessor: usize,
        reason: String,
    },

    /// A vertex attribute holds NaN or infinity.
    #[error(
        "{file}: {mesh} primitive {primitive}: vertex {vertex} has a non-finite {attribute} \
         {value:?}"
    )]
    NonFiniteVertex {
        file: PathBuf,
        mesh: String,
        primitive: usize,
        vertex: usize,
        attribute: &'static str,
        value: Vec<f32>,
    },

    /// An index refers past the end of the primitive's vertex array.
    #[error(
        "{file}: {mesh} primitive {primitive}: index #{position} is {index}, but there are only \
         {vertex_count} vertices"
    )]
    IndexOutOfRange {
        file: PathBuf,
        mesh: String,
        primitive: usize,
        position: usize,
        index: u32,
        vertex_count: usize,
    },

    /// A primitive's index count is not what its mode needs (e.g. TRIANGLES not a multiple of 3).
    #[error("{file}: {mesh} primitive {primitive}: {reason}")]
    InvalidPrimitive {
        file: PathBuf,
        mesh: String,
        primitive: usize,
        reason: String,
    },

    /// A material's image could not be located or decoded.
    /// Every placement of a mesh together is more than the scene may hold (checked before
    /// any is built).
    #[error("{file}: {mesh}: {reason}")]
    InvalidMesh {
        file: PathBuf,
        mesh: String,
        reason: String,
    },

    #[error("{file}: {image} ({slot} of {material}): {reason}")]
    InvalidImage {
        file: PathBuf,
        image: String,
        /// Which of the material's textures uses it: "base color", "emissive", ...
        slot: &'static str,
        material: String,
        reason: String,
    },

    /// A material factor is not a finite f32.
    #[error("{file}: {material}: {reason}")]
    InvalidMaterial {
        file: PathBuf,
        material: String,
        reason: String,
    },

    /// A light's parameters are outside what KHR_lights_punctual allows.
    #[error("{file}: {light}: {reason}")]
    InvalidLight {
        file: PathBuf,
        light: String,
        reason: String,
    },

    /// A camera's parameters cannot make a projection.
    #[error("{file}: {camera}: {reason}")]
    InvalidCamera {
        file: PathBuf,
        camera: String,
        reason: String,
    },

    /// A node's transform is not finite, or puts it beyond
    /// [`MAX_COORDINATE`](super::MAX_COORDINATE).
    #[error("{file}: {node}: {reason}")]
    InvalidNode {
        file: PathBuf,
        node: String,
        reason: String,
    },

    /// Something of the scene lies beyond [`MAX_COORDINATE`](super::MAX_COORDINATE) from the
    /// origin, or its bounds are not finite.
    #[error(
        "{scene}: {what} reaches {value:e}, beyond ±{max:e} (the largest coordinate a scene \
         may have: f64 still resolves 1/8000 unit there, and f32 camera-relative math stays \
         finite)"
    )]
    TooFar {
        scene: String,
        what: String,
        value: f64,
        max: f64,
    },

    /// A node is reached twice from the scene's roots: a cycle or a shared child, both of which
    /// glTF forbids (the hierarchy must be a forest).
    #[error("{file}: {node} is reached twice in the node hierarchy (cycle or shared child)")]
    NodeHierarchy { file: PathBuf, node: String },

    /// More lights than [`MAX_LIGHTS`](super::MAX_LIGHTS).
    #[error("{scene}: more than {max} lights (the most a scene may have: each is drawn as its own volume)")]
    TooManyLights { scene: String, max: u32 },

    /// More particles than [`MAX_PARTICLES`](super::MAX_PARTICLES) over all emitters.
    #[error("{scene}: {count} particles, more than {max} (the most a scene may have: each is an instance of one draw, 32 bytes on the device)")]
    TooManyParticles {
        scene: String,
        count: usize,
        max: usize,
    },

    /// A particle that cannot be drawn (see [`Particle::invalid`](super::Particle::invalid)).
    #[error("{scene}: emitter \"{emitter}\" particle {index}: {reason}")]
    InvalidParticle {
        scene: String,
        emitter: String,
        index: usize,
        reason: String,
    },

    /// Nothing to draw: no triangle survived loading.
    #[error("{scene}: the scene contains no triangles")]
    EmptyScene { scene: String },

    /// `builtin:NAME` with a NAME that is not a built-in scene.
    #[error("unknown built-in scene `{name}`; available: {available}")]
    UnknownBuiltin { name: String, available: String },

    /// A `builtin:NAME?key=value` parameter that the scene does not take or cannot parse.
    #[error("builtin:{scene}: {reason}")]
    BuiltinParameter { scene: String, reason: String },
}

/// How errors and warnings name a glTF object: its kind and index, plus its name when it has one
/// (names are optional and not unique, indices are what a glTF validator reports).
pub(crate) fn label(kind: &str, index: usize, name: Option<&str>) -> String {
    match name {
        Some(name) => format!("{kind} {index} \"{name}\""),
        None => format!("{kind} {index}"),
    }
}
