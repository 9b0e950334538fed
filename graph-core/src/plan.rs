//! The compiled plan: plain, serializable data saying what runs, in what order, with which
//! load/store operations, on which physical textures, and why anything was left out.
//! `rgraph explain` prints it; the executor follows it.

use serde::Serialize;
use wgpu_types::{BufferUsages, TextureUsages};

use crate::access::DroppedRead;
use crate::handle::{Kind, PassId, ResourceId};
use crate::pass::PassKind;
use crate::resource::{Origin, TextureShape};

/// What one compile decided, for one output size, device profile and feature set. Plain
/// data: it owns no GPU object, can be printed ([`explain`](crate::explain)), serialized
/// and compared, and stays valid for as long as the graph it was compiled from is
/// unchanged (which [`CompiledGraph`](crate::CompiledGraph) guarantees).
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
    /// Graph-owned memory before and after resources share physical objects.
    pub memory: MemoryReport,
    /// What this frame hands the next: one edge per history whose source runs.
    pub history: Vec<HistoryEdge>,
    /// A digest of the rest of the plan when it has histories (0 when it has none). The
    /// executor keeps histories only from one frame to the next of plans with the same
    /// fingerprint: any other plan (a resize, other features, another graph) reads the
    /// reset value. Stable within one build of rgraph-core, not across versions.
    pub fingerprint: u64,
}

/// A history's edge to the next frame: this frame's final version of `source`, which
/// `writer` produces, is what `readers` read as `history` in the next frame. Both live in
/// a pair of textures the executor keeps for the history alone (never pooled or shared),
/// swapped after each frame.
#[derive(Clone, Debug, Serialize)]
pub struct HistoryEdge {
    /// The resource carried: written this frame.
    pub source: ResourceId,
    /// The history resource: read this frame, holding `source` as the last frame left it.
    pub history: ResourceId,
    /// The version of `source` carried: the one `writer` produces.
    pub version: u32,
    /// The one pass that writes `source`.
    pub writer: String,
    /// The live passes that read the previous frame's contents, in execution order (none
    /// when no pass reads the history in this plan; the source is still carried).
    pub readers: Vec<String>,
    /// The shape of both textures of the pair.
    pub shape: TextureShape,
    /// The usages of both textures: each is the source one frame and the history the next.
    pub usage: TextureUsages,
    /// Bytes of one texture of the pair.
    pub bytes: u64,
}

/// A pass that runs, with what the compiler inferred for it.
#[derive(Clone, Debug, Serialize)]
pub struct PlannedPass {
    /// The pass in the declared graph.
    pub id: PassId,
    /// Its declared name.
    pub name: String,
    /// The kind of wgpu pass the executor begins.
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
    /// The depth-stencil attachment (render passes that declared one).
    pub depth_stencil: Option<DepthStencilAttachment>,
    /// A compute pass's workgroup size and memory for each entry point it dispatches.
    pub workgroups: Vec<crate::pass::Workgroup>,
    /// Its optional reads and fresh writes
    /// ([`PassBuilder::optional`](crate::PassBuilder::optional)) this plan leaves out,
    /// with why: the pass runs without them, and its recording finds them missing
    /// (`FrameResources::has` is false).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub dropped_reads: Vec<DroppedRead>,
    /// Where the pass was written, when not in the graph's own file (see
    /// [`PassBuilder::origin`](crate::PassBuilder::origin)).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub origin: Option<String>,
}

impl PlannedPass {
    /// Whether this plan leaves `access`, one the pass declared, out: an optional read or
    /// write in [`dropped_reads`](Self::dropped_reads).
    pub fn drops(&self, access: &crate::access::Access) -> bool {
        self.dropped_reads.iter().any(|d| d.covers(access))
    }

    /// Whether the pass reads some version of `resource` in this plan (an optional read
    /// the plan drops is not one).
    pub fn reads_resource(&self, resource: ResourceId) -> bool {
        self.reads.iter().any(|&(r, _)| r == resource)
    }

    /// Whether the pass writes some version of `resource` in this plan.
    pub fn writes_resource(&self, resource: ResourceId) -> bool {
        self.writes.iter().any(|&(r, _)| r == resource)
    }
}

/// How an attachment aspect begins.
#[derive(Copy, Clone, Debug, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Load<T> {
    /// Cleared to this value (wgpu's `LoadOp::Clear`).
    Clear(T),
    /// The previous contents are kept, because the pass reads them (`LoadOp::Load`).
    Load,
    /// Neither cleared nor read: the pass overwrites what later passes read
    /// ([`AspectAccess::Overwrite`](crate::AspectAccess::Overwrite)); the device loads.
    Overwrite,
}

/// Whether an attachment's contents are kept after the pass.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Store {
    /// Kept: a later pass reads this version, or it is imported or exported.
    Store,
    /// Discarded: nothing reads what the pass left (a depth buffer used only for testing
    /// within the pass, a multisampled color attachment that was resolved).
    Discard,
}

/// Load and store of one written attachment aspect.
#[derive(Copy, Clone, Debug, PartialEq, Serialize)]
pub struct Ops<T> {
    /// How the aspect begins.
    pub load: Load<T>,
    /// Whether it is kept after the pass.
    pub store: Store,
}

/// One color attachment of a planned render pass.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ColorAttachment {
    /// The texture attached.
    pub resource: ResourceId,
    /// Its inferred load and store (clear values as linear RGBA, 0 to 1 for unorm formats).
    pub ops: Ops<[f64; 4]>,
    /// The single-sampled texture it is resolved into at the end of the pass, if any.
    pub resolve_target: Option<ResourceId>,
}

/// The depth-stencil attachment of a planned render pass. `None` for an aspect means it
/// is attached read-only (or the format lacks it).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct DepthStencilAttachment {
    /// The texture attached.
    pub resource: ResourceId,
    /// Depth load and store; clear values in the format's 0 to 1 range.
    pub depth: Option<Ops<f32>>,
    /// Stencil load and store; clear values are the stencil reference value.
    pub stencil: Option<Ops<u32>>,
}

/// A declared pass that does not run in this plan.
#[derive(Clone, Debug, Serialize)]
pub struct CulledPass {
    /// The pass in the declared graph.
    pub id: PassId,
    /// Its declared name.
    pub name: String,
    /// Its kind.
    pub kind: PassKind,
    /// Why, in words: the false condition, the omission's reason, or that nothing reads
    /// what it writes.
    pub reason: String,
    /// Dropped because its condition is false for the plan's features, rather than
    /// culled because nothing needs what it writes.
    pub dropped: bool,
    /// The versions it would have read, as `(resource, version)`, so drawings can show
    /// the dead branch.
    pub reads: Vec<(ResourceId, u32)>,
    /// The versions it would have produced, as `(resource, version)`.
    pub writes: Vec<(ResourceId, u32)>,
}

/// A declared resource as the plan resolved it. Every declared resource has one, even
/// when no live pass uses it ([`culled`](Self::culled) then says why).
#[derive(Clone, Debug, Serialize)]
pub struct PlannedResource {
    /// The resource in the declared graph; also its index in [`Plan::resources`].
    pub id: ResourceId,
    /// Its declared name.
    pub name: String,
    /// Texture or buffer.
    pub kind: Kind,
    /// Graph-owned (pooled) or imported (bound by the engine at execution).
    pub origin: Origin,
    /// Exported: its final version is readable after the frame.
    pub exported: bool,
    /// Set for textures.
    pub texture: Option<TextureShape>,
    /// Set for buffers: the size in bytes.
    pub buffer_size: Option<u64>,
    /// Every usage its live accesses need (textures); what an imported texture must have.
    pub texture_usage: TextureUsages,
    /// Every usage its live accesses need, plus `extra_usage` (buffers).
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

/// A texture the executor allocates from its pool for this plan.
#[derive(Clone, Debug, Serialize)]
pub struct PhysicalTexture {
    /// Format, size, samples, mips and layers: the same for every resource it holds.
    pub shape: TextureShape,
    /// The union of the usages of the resources it holds.
    pub usage: TextureUsages,
    /// Its size in memory ([`TextureDesc::bytes`](crate::TextureDesc::bytes)).
    pub bytes: u64,
    /// The resources that live in it, in lifetime order.
    pub holds: Vec<ResourceId>,
}

/// A buffer the executor allocates from its pool for this plan.
#[derive(Clone, Debug, Serialize)]
pub struct PhysicalBuffer {
    /// Bytes.
    pub size: u64,
    /// The union of the usages of the resources it holds.
    pub usage: BufferUsages,
    /// The resources that live in it, in lifetime order.
    pub holds: Vec<ResourceId>,
}

/// Memory of graph-owned resources before and after sharing.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize)]
pub struct MemoryReport {
    /// Every live graph-owned resource on its own (a history's pair counts twice).
    pub logical_bytes: u64,
    /// What the executor allocates, histories' pairs included.
    pub physical_bytes: u64,
}

impl Plan {
    /// The planned resource for `id`.
    ///
    /// # Panics
    /// When `id` is not a resource of the graph this plan was compiled from.
    pub fn resource(&self, id: ResourceId) -> &PlannedResource {
        &self.resources[id.index()]
    }

    /// The resource called `name`.
    pub fn find(&self, name: &str) -> Option<&PlannedResource> {
        self.resources.iter().find(|r| r.name == name)
    }

    /// The edge to the next frame of the history `id`, or of the source it carries.
    pub fn history_edge(&self, id: ResourceId) -> Option<&HistoryEdge> {
        self.history
            .iter()
            .find(|e| e.history == id || e.source == id)
    }

    /// The planned pass called `name`, if it runs.
    pub fn pass(&self, name: &str) -> Option<&PlannedPass> {
        self.passes.iter().find(|p| p.name == name)
    }
}
