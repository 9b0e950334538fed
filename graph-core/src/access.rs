//! Access roles: how a pass touches a resource. The compiler derives usages, load/store
//! operations and ordering from these and nothing else.

use std::fmt;

use serde::{Serialize, Serializer};
use wgpu_types::{BufferUsages, TextureFormat, TextureUsages};

use crate::handle::ResourceId;

/// How a color attachment begins.
#[derive(Copy, Clone, Debug, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ColorLoad {
    /// Clear to this RGBA value: the previous contents are not read.
    Clear([f64; 4]),
    /// Keep the previous contents (the pass reads the version it writes over).
    Load,
    /// Neither clear nor read: the pass draws every texel later passes read (a full-screen
    /// draw), as [`AspectAccess::Overwrite`] for depth.
    Overwrite,
}

/// How a pass uses one aspect (depth or stencil) of a depth-stencil attachment.
#[derive(Copy, Clone, Debug, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum AspectAccess<T> {
    /// Tested against, never written: the pass reads the incoming version.
    ReadOnly,
    /// Written after a clear to this value: the incoming contents are not read.
    Clear(T),
    /// As `Clear`, to the value [`ByFormat`] gives for the format the compile picks.
    ClearByFormat(ByFormat<T>),
    /// Written on top of the incoming contents.
    Load,
    /// Written where the pass draws, over contents nothing reads: the incoming version is
    /// not read (as with `Clear`), and what the pass leaves undrawn is undefined, so later
    /// passes must read only what it draws. For a pass that draws every texel later passes
    /// read (a full-screen draw, or one scissored to where they read): a clear of a
    /// multisampled target goes through the ROPs, which on a chip with few of them (the
    /// H200) costs as much as a full-screen pass.
    Overwrite,
    /// The format has no such aspect (the stencil of `depth32float`, the depth of
    /// `stencil8`): neither read nor written, so it orders nothing.
    /// [`PassBuilder::depth_stencil`](crate::PassBuilder::depth_stencil) turns a `ReadOnly`
    /// access to a missing aspect into this, which is what wgpu's `None` ops mean there.
    Absent,
}

impl<T> AspectAccess<T> {
    /// Whether the access produces a new version of the aspect (a clear, a load or an
    /// overwrite): the pass's depth-stencil handle then moves to a new version.
    pub fn writes(&self) -> bool {
        matches!(
            self,
            AspectAccess::Clear(_)
                | AspectAccess::ClearByFormat(_)
                | AspectAccess::Load
                | AspectAccess::Overwrite
        )
    }
    /// Whether the access depends on the incoming contents (`ReadOnly`, `Load`), which
    /// orders the pass after the aspect's previous writer.
    pub fn reads(&self) -> bool {
        matches!(self, AspectAccess::ReadOnly | AspectAccess::Load)
    }
}

/// A clear value that depends on the texture's format, resolved when the graph is
/// compiled (load/store inference). Why: at declaration a pass cannot know the format it
/// will get, since a fallback (the device decides) or a conditional format (the scene's
/// features decide) may replace the declared one; and what "cleared" means can depend on
/// the format: a depth buffer whose depth convention follows its format (reversed-Z for
/// float depth) clears to that convention's far value.
///
/// A plain function, so that accesses stay `Copy` and comparable.
#[derive(Copy, Clone)]
pub struct ByFormat<T>(pub fn(TextureFormat) -> T);

impl<T> ByFormat<T> {
    /// The value for a texture of `format`.
    pub fn value(&self, format: TextureFormat) -> T {
        (self.0)(format)
    }
}

impl<T> PartialEq for ByFormat<T> {
    /// The same function.
    fn eq(&self, other: &Self) -> bool {
        std::ptr::fn_addr_eq(self.0, other.0)
    }
}

impl<T> fmt::Debug for ByFormat<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("ByFormat(..)")
    }
}

impl<T> Serialize for ByFormat<T> {
    /// As `"by_format"`: the value is known only once the format is.
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str("by_format")
    }
}

/// Which aspect of a depth-stencil texture a sampled view shows.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, Serialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum Aspect {
    /// Every aspect the format has: the full view.
    #[default]
    All,
    /// The depth aspect alone (`texture_depth_2d` in WGSL).
    DepthOnly,
    /// The stencil aspect alone (a `u32` texture in WGSL).
    StencilOnly,
}

/// A pass's use of a texture.
#[derive(Copy, Clone, Debug, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum TextureRole {
    /// Color attachment at this location.
    Color {
        /// `@location` in the fragment shader's output: the attachment's index.
        location: u32,
        /// How the attachment begins, which decides whether the pass reads it.
        load: ColorLoad,
    },
    /// Resolve target of the multisampled color attachment at this location.
    Resolve {
        /// The location of the multisampled color attachment resolved into it.
        location: u32,
    },
    /// The depth-stencil attachment.
    DepthStencil {
        /// The depth aspect's access; its clear value is in the format's units (0 to 1).
        depth: AspectAccess<f32>,
        /// The stencil aspect's access; its clear value is the 8-bit reference value.
        stencil: AspectAccess<u32>,
    },
    /// Bound for sampling or `textureLoad` (multisampled textures included).
    Sampled {
        /// The aspect the view shows.
        aspect: Aspect,
    },
    /// Bound as a storage texture.
    Storage {
        /// The pass reads the incoming contents.
        read: bool,
        /// The pass produces a new version.
        write: bool,
    },
    /// The source of a copy (a transfer pass's).
    CopySrc,
    /// The destination of a copy: a new version, the incoming contents not read.
    CopyDst,
}

/// A pass's use of a buffer.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum BufferRole {
    /// Bound as a vertex buffer (read).
    Vertex,
    /// Bound as an index buffer (read).
    Index,
    /// Bound as a uniform buffer (read).
    Uniform,
    /// The arguments of an indirect draw or dispatch (read).
    Indirect,
    /// Bound as a storage buffer.
    Storage {
        /// The pass reads the incoming contents.
        read: bool,
        /// The pass produces a new version.
        write: bool,
    },
    /// The source of a copy (read).
    CopySrc,
    /// The destination of a copy: a new version, the incoming contents not read.
    CopyDst,
}

/// A role of either kind.
#[derive(Copy, Clone, Debug, PartialEq, Serialize)]
#[serde(untagged)]
pub enum Role {
    /// An access to a texture.
    Texture(TextureRole),
    /// An access to a buffer.
    Buffer(BufferRole),
}

impl Role {
    /// Whether the pass depends on the version it was given.
    pub fn reads(&self) -> bool {
        match *self {
            Role::Texture(TextureRole::Color { load, .. }) => load == ColorLoad::Load,
            Role::Texture(TextureRole::Resolve { .. }) => false,
            Role::Texture(TextureRole::DepthStencil { depth, stencil }) => {
                depth.reads() || stencil.reads()
            }
            Role::Texture(TextureRole::Sampled { .. }) => true,
            Role::Texture(TextureRole::Storage { read, .. }) => read,
            Role::Texture(TextureRole::CopySrc) => true,
            Role::Texture(TextureRole::CopyDst) => false,
            Role::Buffer(BufferRole::Storage { read, .. }) => read,
            Role::Buffer(BufferRole::CopyDst) => false,
            Role::Buffer(_) => true,
        }
    }

    /// Whether the pass produces a new version.
    pub fn writes(&self) -> bool {
        match *self {
            Role::Texture(TextureRole::Color { .. })
            | Role::Texture(TextureRole::Resolve { .. })
            | Role::Texture(TextureRole::CopyDst)
            | Role::Buffer(BufferRole::CopyDst) => true,
            Role::Texture(TextureRole::DepthStencil { depth, stencil }) => {
                depth.writes() || stencil.writes()
            }
            Role::Texture(TextureRole::Storage { write, .. })
            | Role::Buffer(BufferRole::Storage { write, .. }) => write,
            _ => false,
        }
    }

    /// Whether this role binds the texture as a render-pass attachment.
    pub fn is_attachment(&self) -> bool {
        matches!(
            self,
            Role::Texture(
                TextureRole::Color { .. }
                    | TextureRole::Resolve { .. }
                    | TextureRole::DepthStencil { .. }
            )
        )
    }

    /// The texture usage this role needs (empty for buffer roles).
    pub fn texture_usage(&self) -> TextureUsages {
        match self {
            Role::Texture(TextureRole::Color { .. })
            | Role::Texture(TextureRole::Resolve { .. })
            | Role::Texture(TextureRole::DepthStencil { .. }) => TextureUsages::RENDER_ATTACHMENT,
            Role::Texture(TextureRole::Sampled { .. }) => TextureUsages::TEXTURE_BINDING,
            Role::Texture(TextureRole::Storage { .. }) => TextureUsages::STORAGE_BINDING,
            Role::Texture(TextureRole::CopySrc) => TextureUsages::COPY_SRC,
            Role::Texture(TextureRole::CopyDst) => TextureUsages::COPY_DST,
            Role::Buffer(_) => TextureUsages::empty(),
        }
    }

    /// The buffer usage this role needs (empty for texture roles).
    pub fn buffer_usage(&self) -> BufferUsages {
        match self {
            Role::Buffer(BufferRole::Vertex) => BufferUsages::VERTEX,
            Role::Buffer(BufferRole::Index) => BufferUsages::INDEX,
            Role::Buffer(BufferRole::Uniform) => BufferUsages::UNIFORM,
            Role::Buffer(BufferRole::Indirect) => BufferUsages::INDIRECT,
            Role::Buffer(BufferRole::Storage { .. }) => BufferUsages::STORAGE,
            Role::Buffer(BufferRole::CopySrc) => BufferUsages::COPY_SRC,
            Role::Buffer(BufferRole::CopyDst) => BufferUsages::COPY_DST,
            Role::Texture(_) => BufferUsages::empty(),
        }
    }

    /// A short role name for messages: "color attachment", "sampled", ...
    pub fn describe(&self) -> &'static str {
        match self {
            Role::Texture(TextureRole::Color { .. }) => "color attachment",
            Role::Texture(TextureRole::Resolve { .. }) => "resolve target",
            Role::Texture(TextureRole::DepthStencil { .. }) => "depth-stencil attachment",
            Role::Texture(TextureRole::Sampled { .. }) => "sampled texture",
            Role::Texture(TextureRole::Storage { .. }) => "storage texture",
            Role::Texture(TextureRole::CopySrc) | Role::Buffer(BufferRole::CopySrc) => {
                "copy source"
            }
            Role::Texture(TextureRole::CopyDst) | Role::Buffer(BufferRole::CopyDst) => {
                "copy destination"
            }
            Role::Buffer(BufferRole::Vertex) => "vertex buffer",
            Role::Buffer(BufferRole::Index) => "index buffer",
            Role::Buffer(BufferRole::Uniform) => "uniform buffer",
            Role::Buffer(BufferRole::Indirect) => "indirect buffer",
            Role::Buffer(BufferRole::Storage { .. }) => "storage buffer",
        }
    }
}

/// One declared access: a pass used `resource` in `role`, reading version `read` (if the
/// role reads) and producing version `written` (if the role writes).
#[derive(Copy, Clone, Debug, PartialEq, Serialize)]
pub struct Access {
    /// The resource accessed.
    pub resource: ResourceId,
    /// How: what the compiler derives usages, ordering and load/store from.
    pub role: Role,
    /// The version the pass was handed.
    pub version: u32,
    /// The version the pass produces, when the role writes.
    pub written: Option<u32>,
    /// A read the pass can do without
    /// ([`PassBuilder::optional`](crate::PassBuilder::optional)): where a condition drops
    /// the resource or the pass that alone wrote the version read, the compile drops this
    /// access rather than failing, and the plan says so
    /// ([`PlannedPass::dropped_reads`](crate::plan::PlannedPass::dropped_reads)).
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub optional: bool,
}

impl Access {
    /// The version this access depends on, if it reads.
    pub fn read_version(&self) -> Option<u32> {
        self.role.reads().then_some(self.version)
    }
}

/// An optional access a plan leaves out of its pass, because a condition dropped what it
/// reads (or, for a fresh write, the resource it writes).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct DroppedRead {
    /// The resource the pass would have read or written.
    pub resource: ResourceId,
    /// The version it declared.
    pub version: u32,
    /// Why: `"shadow_atlas" is dropped: condition "shadows" is false`, or the dropped
    /// pass that alone writes it and that pass's reason.
    pub why: String,
    /// The access was a fresh write (an output the plan does without), not a read.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub writes: bool,
}

impl DroppedRead {
    /// Whether `access`, one its pass declared, is this read.
    pub fn covers(&self, access: &Access) -> bool {
        access.optional && access.resource == self.resource && access.version == self.version
    }
}
