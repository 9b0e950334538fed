//! The compiled plan: plain, serializable data saying what runs, in what order, with which
//! load/store operations, on which physical textures, and why anything was left out.
//! `rgraph explain` prints it; the executor follows it.

use serde::Serialize;
use wgpu_types::{BufferUsages, TextureUsages};

use crate::handle::{Kind, PassId, ResourceId};
use crate::pass::PassKind;
use crate::resource::{Origin, TextureShape};

#[derive(Clone, Debug, Serialize)]
pub struct Plan {
    /// The output size relative sizes were resolved against.
    pub output_size: (u32, u32),
    /// The device profile the graph was validated against.
    pub profile: String,
    /// The declared features the plan was compiled for: conditions over them decided
    /// which passes and resources are in it.
    pub features: Vec<String>,
    /// Passes that run, in execution order.
    pub passes: Vec<PlannedPass>,
    /// Passes that do not run, with the reason (a false condition, or nothing needing
    /// what they write), in declaration order.
    pub culled: Vec<CulledPass>,
    /// Every declared resource, indexed by [`ResourceId`].
    pub resources: Vec<PlannedResource>,
    /// Textures the executor allocates; several resources may share one.
    pub textures: Vec<PhysicalTexture>,
    /// Buffers the executor allocates.
    pub buffers: Vec<PhysicalBuffer>,
    pub memory: MemoryReport,
}

#[derive(Clone, Debug, Serialize)]
pub struct PlannedPass {
    pub id: PassId,
    pub name: String,
    pub kind: PassKind,
    /// Versions read, as `(resource, version)`.
    pub reads: Vec<(ResourceId, u32)>,
    /// Versions produced, as `(resource, version)`.
    pub writes: Vec<(ResourceId, u32)>,
    /// Color attachments by location (render passes only).
    pub color: Vec<ColorAttachment>,
    /// What the color attachments cost per sample against the device's
    /// `max_color_attachment_bytes_per_sample` (a G-buffer's size per sample).
    pub color_bytes_per_sample: u32,
    /// What one sample of the attachments, color and depth-stencil, occupies in memory
    /// ([`texel_bytes`](crate::resource::texel_bytes): D32S8 counts 8): a G-buffer's real
    /// size per sample, which `color_bytes_per_sample`'s alignment rules overstate and its
    /// leaving out depth understates. Buffers sized per sample that the pass writes add
    /// their bytes per sample (a visibility buffer rasterised in compute).
    pub stored_bytes_per_sample: u32,
    pub depth_stencil: Option<DepthStencilAttachment>,
    /// A compute pass's workgroup size and memory for each entry point it dispatches.
    pub workgroups: Vec<crate::pass::Workgroup>,
}

/// How an attachment aspect begins.
#[derive(Copy, Clone, Debug, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Load<T> {
    Clear(T),
    Load,
    /// Neither cleared nor read: the pass overwrites what later passes read
    /// ([`AspectAccess::Overwrite`](crate::AspectAccess::Overwrite)); the device loads.
    Overwrite,
}

/// Whether an attachment's contents are kept after the pass.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Store {
    Store,
    Discard,
}

/// Load and store of one written attachment aspect.
#[derive(Copy, Clone, Debug, PartialEq, Serialize)]
pub struct Ops<T> {
    pub load: Load<T>,
    pub store: Store,
}

#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ColorAttachment {
    pub resource: ResourceId,
    pub ops: Ops<[f64; 4]>,
    pub resolve_target: Option<ResourceId>,
}

/// `None` for an aspect means it is attached read-only.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct DepthStencilAttachment {
    pub resource: ResourceId,
    pub depth: Option<Ops<f32>>,
    pub stencil: Option<Ops<u32>>,
}

#[derive(Clone, Debug, Serialize)]
pub struct CulledPass {
    pub id: PassId,
    pub name: String,
    pub kind: PassKind,
    pub reason: String,
    /// Dropped because its condition is false for the plan's features, rather than
    /// culled because nothing needs what it writes.
    pub dropped: bool,
    /// What it would have read and written, so drawings can show the dead branch.
    pub reads: Vec<(ResourceId, u32)>,
    pub writes: Vec<(ResourceId, u32)>,
}

#[derive(Clone, Debug, Serialize)]
pub struct PlannedResource {
    pub id: ResourceId,
    pub name: String,
    pub kind: Kind,
    pub origin: Origin,
    pub exported: bool,
    /// Set for textures.
    pub texture: Option<TextureShape>,
    /// Set for buffers: the size in bytes.
    pub buffer_size: Option<u64>,
    pub texture_usage: TextureUsages,
    pub buffer_usage: BufferUsages,
    /// First and last position in [`Plan::passes`] that use it; `None` when unused.
    pub lifetime: Option<(usize, usize)>,
    /// Index into [`Plan::textures`] or [`Plan::buffers`]; `None` for imported or unused
    /// resources.
    pub physical: Option<usize>,
    /// Why the resource is not allocated, when it is not.
    pub culled: Option<String>,
    /// Why the texture has a conditional format rather than the one declared
    /// (`depth24plus-stencil8 instead of depth32float-stencil8: condition "shallow_depth"
    /// holds`), when it has.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub format_because: Option<String>,
    /// Bytes the resource would take on its own.
    pub bytes: u64,
}

#[derive(Clone, Debug, Serialize)]
pub struct PhysicalTexture {
    pub shape: TextureShape,
    pub usage: TextureUsages,
    pub bytes: u64,
    /// The resources that live in it, in lifetime order.
    pub holds: Vec<ResourceId>,
}

#[derive(Clone, Debug, Serialize)]
pub struct PhysicalBuffer {
    pub size: u64,
    pub usage: BufferUsages,
    pub holds: Vec<ResourceId>,
}

/// Memory of graph-owned resources before and after sharing.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize)]
pub struct MemoryReport {
    /// Every live graph-owned resource on its own.
    pub logical_bytes: u64,
    /// What the executor allocates.
    pub physical_bytes: u64,
}

impl Plan {
    pub fn resource(&self, id: ResourceId) -> &PlannedResource {
        &self.resources[id.index()]
    }

    /// The resource called `name`.
    pub fn find(&self, name: &str) -> Option<&PlannedResource> {
        self.resources.iter().find(|r| r.name == name)
    }

    /// The planned pass called `name`, if it runs.
    pub fn pass(&self, name: &str) -> Option<&PlannedPass> {
        self.passes.iter().find(|p| p.name == name)
    }
}
