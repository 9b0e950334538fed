//! Declaring a graph: resources first, then passes that access them through handles.

use crate::access::{Access, Aspect, AspectAccess, BufferRole, ColorLoad, Role, TextureRole};
use crate::condition::{Condition, Features};
use crate::error::GraphError;
use crate::handle::{
    BufferHandle, Handle, PassId, ResourceId, ResourceKind, Texture, TextureHandle,
};
use crate::pass::{PassKind, PassNode};
use crate::resource::{BufferDesc, Origin, ResourceDesc, ResourceNode, TextureDesc};

/// A graph being declared. Declaring never fails and never touches a GPU: mistakes are
/// recorded and reported, all together, by [`Graph::compile`](crate::graph::Graph::compile).
#[derive(Default)]
pub struct GraphBuilder {
    pub(crate) resources: Vec<ResourceNode>,
    pub(crate) passes: Vec<PassNode>,
    /// The feature names conditions may use.
    pub(crate) features: Features,
    pub(crate) errors: Vec<GraphError>,
}

impl GraphBuilder {
    /// An empty graph with no feature declared.
    pub fn new() -> Self {
        Self::default()
    }

    /// A graph-owned texture. Its contents are undefined until a pass writes it, and its
    /// memory may be shared with other textures whose lifetimes do not overlap.
    pub fn create_texture(&mut self, name: impl Into<String>, desc: TextureDesc) -> TextureHandle {
        self.add_resource(name.into(), ResourceDesc::Texture(desc), Origin::Transient)
    }

    /// A graph-owned buffer.
    pub fn create_buffer(&mut self, name: impl Into<String>, desc: BufferDesc) -> BufferHandle {
        self.add_resource(name.into(), ResourceDesc::Buffer(desc), Origin::Transient)
    }

    /// An engine-owned texture, bound by name or id when the graph executes. The engine
    /// keeps ownership; the description must match what it binds (checked at execution).
    pub fn import_texture(&mut self, name: impl Into<String>, desc: TextureDesc) -> TextureHandle {
        self.add_resource(name.into(), ResourceDesc::Texture(desc), Origin::Imported)
    }

    /// An engine-owned buffer.
    pub fn import_buffer(&mut self, name: impl Into<String>, desc: BufferDesc) -> BufferHandle {
        self.add_resource(name.into(), ResourceDesc::Buffer(desc), Origin::Imported)
    }

    /// The previous frame's contents of `of`, a graph-owned texture: a history, read-only
    /// this frame (its version 0), with `of`'s description. `of` becomes this frame's
    /// export and the next frame's import: the one pass that writes it each frame writes
    /// what the next frame reads through the returned handle. Passes may read the history
    /// anywhere in the frame, before or after `of` is written, also in the pass that
    /// writes `of` (a temporal filter): the executor keeps the two in textures of their
    /// own, which no other resource shares, and swaps them after each frame.
    ///
    /// The first frame, and the first after a resize, a change of plan or
    /// [`Executor::reset_history`](crate::gpu::Executor::reset_history), reads zeros; a
    /// pass asks [`FrameResources::history_reset`] whether this frame's is such a reset.
    /// The history exists where `of` does: without a condition of its own it takes `of`'s
    /// when the graph is built.
    ///
    /// Compiling checks that exactly one pass writes `of`, once (one version), that no
    /// pass writes the history, and that `of` has no other history.
    ///
    /// [`FrameResources::history_reset`]: crate::gpu::FrameResources::history_reset
    pub fn history_texture(&mut self, name: impl Into<String>, of: TextureHandle) -> TextureHandle {
        let desc = match self.resources.get_mut(of.id.index()) {
            Some(source) => {
                source.exported = true;
                source.desc.clone()
            }
            None => ResourceDesc::Texture(TextureDesc::new(wgpu_types::TextureFormat::R8Unorm)),
        };
        self.add_resource(name.into(), desc, Origin::History { of: of.id })
    }

    /// Keeps the resource's final contents past the frame (readback, history): it is a
    /// culling root, its memory is never lent to another resource, and it can be copied
    /// from after execution.
    pub fn export<K: ResourceKind>(&mut self, handle: Handle<K>) {
        if let Some(node) = self.resources.get_mut(handle.id.index()) {
            node.exported = true;
        }
    }

    /// Declares feature names that conditions ([`when`](Self::when),
    /// [`PassBuilder::when`]) may use. A condition naming any other feature is a compile
    /// error, so a misspelt feature cannot silently drop a pass.
    pub fn declare_features<S: Into<String>>(&mut self, features: impl IntoIterator<Item = S>) {
        for feature in features {
            self.features.insert(feature);
        }
    }

    /// Makes the resource exist only where `condition` holds for the features the graph
    /// is compiled for. Passes that use it must not be in the graph without it: give
    /// them a condition that implies this one.
    pub fn when<K: ResourceKind>(&mut self, handle: Handle<K>, condition: Condition) {
        if let Some(node) = self.resources.get_mut(handle.id.index()) {
            node.condition = Some(condition);
        }
    }

    /// Starts a render pass. Attachments are declared on the returned builder; the
    /// executor begins the wgpu render pass with them before calling the record callback.
    pub fn add_render_pass(&mut self, name: impl Into<String>) -> PassBuilder<'_> {
        self.add_pass(name.into(), PassKind::Render)
    }

    /// Starts a compute pass.
    pub fn add_compute_pass(&mut self, name: impl Into<String>) -> PassBuilder<'_> {
        self.add_pass(name.into(), PassKind::Compute)
    }

    /// Starts a transfer pass (copies; the callback gets the command encoder).
    pub fn add_transfer_pass(&mut self, name: impl Into<String>) -> PassBuilder<'_> {
        self.add_pass(name.into(), PassKind::Transfer)
    }

    /// The declared resource behind a handle.
    pub fn resource<K: ResourceKind>(&self, handle: Handle<K>) -> &ResourceNode {
        &self.resources[handle.id.index()]
    }

    /// Finishes declaring. The graph can then be compiled (and recompiled for other
    /// output sizes or profiles) without a GPU.
    pub fn build(mut self) -> crate::graph::Graph {
        // A history exists where its source does, unless it says otherwise.
        for r in 0..self.resources.len() {
            let source = self.resources[r].origin.history_of();
            if self.resources[r].condition.is_none() {
                let inherited = source
                    .and_then(|of| self.resources.get(of.index()))
                    .and_then(|of| of.condition.clone());
                self.resources[r].condition = inherited;
            }
        }
        crate::graph::Graph {
            resources: self.resources,
            passes: self.passes,
            features: self.features,
            declare_errors: self.errors,
        }
    }

    fn add_resource<K: ResourceKind>(
        &mut self,
        name: String,
        desc: ResourceDesc,
        origin: Origin,
    ) -> Handle<K> {
        let id = ResourceId(self.resources.len() as u32);
        self.resources.push(ResourceNode {
            name,
            desc,
            origin,
            exported: false,
            condition: None,
            versions: 1,
        });
        Handle::new(id, 0)
    }

    fn add_pass(&mut self, name: String, kind: PassKind) -> PassBuilder<'_> {
        let id = PassId(self.passes.len() as u32);
        self.passes.push(PassNode::new(name, kind));
        PassBuilder { graph: self, id }
    }
}

/// Declares one pass's accesses. Role-named verbs return the handle of the version the
/// pass produces; keep using the handle they were given only to read older contents.
pub struct PassBuilder<'g> {
    graph: &'g mut GraphBuilder,
    id: PassId,
}

impl PassBuilder<'_> {
    /// This pass's id.
    pub fn id(&self) -> PassId {
        self.id
    }

    /// Runs the pass only where `condition` holds for the features the graph is compiled
    /// for. Where it does not, the pass is dropped: what it modifies passes through
    /// unchanged (readers of its output read its input), and passes writing the same
    /// version under an exclusive condition stand in for it.
    pub fn when(&mut self, condition: Condition) -> &mut Self {
        self.node().condition = Some(condition);
        self
    }

    /// The condition set by [`when`](Self::when), if any: plugins check the formats a
    /// texture may have where it holds ([`TextureDesc::formats_where`]).
    pub fn condition(&self) -> Option<&Condition> {
        self.graph.passes[self.id.index()].condition.as_ref()
    }

    /// Says where the pass was written, for `explain`: a graph file's loader names the part
    /// a pass came from and where the graph uses it.
    pub fn origin(&mut self, origin: impl Into<String>) -> &mut Self {
        self.node().origin = Some(origin.into());
        self
    }

    /// Leaves the pass out of every plan, as a false condition would (what it modifies
    /// passes through; explain shows `reason`), with its accesses still declared and
    /// checked. For a plugin that finds at setup that its work is empty, such as edge
    /// detection with one sample per pixel, so a pipeline file serves every sample
    /// count without running passes that do nothing.
    pub fn omit(&mut self, reason: impl Into<String>) -> &mut Self {
        self.node().omitted = Some(reason.into());
        self
    }

    /// Declares what a compute entry point the pass dispatches asks of the device
    /// ([`Entry::workgroup`](crate::shader::Entry::workgroup)), once for each it
    /// dispatches: compiling checks each against the profile's
    /// `max_compute_workgroup_storage_size`, invocations and workgroup dimensions, and
    /// fails naming the pass and the entry point. Declaring one again is a no-op: a pass
    /// set up in variants (with and without an optional input) declares each variant's.
    pub fn workgroup(&mut self, workgroup: crate::pass::Workgroup) -> &mut Self {
        if !self.node().workgroups.contains(&workgroup) {
            self.node().workgroups.push(workgroup);
        }
        self
    }

    /// Makes the pass's reads of `handle` (the accesses declared so far to that version)
    /// optional: where a condition drops the resource, or the pass that alone wrote that
    /// version, the compile drops these accesses instead of failing with
    /// [`GraphError::DroppedWriter`] or [`GraphError::UsesDroppedResource`], and the
    /// plan lists them in [`PlannedPass::dropped_reads`](crate::plan::PlannedPass::dropped_reads)
    /// with the reason (`explain` prints it). The pass runs either way: it must work
    /// without the input, asking `FrameResources::has` (feature `gpu`) while it records,
    /// before it builds what binds the input. Where the writer stays, the read is an
    /// ordinary one.
    ///
    /// A fresh write (one that reads nothing of the version it writes over: a color
    /// attachment cleared or covered, a storage write) may be optional too: where a
    /// condition drops the resource, the compile drops the write, and the pass runs
    /// without that output (a G-buffer pass writes a target only scenes that need it
    /// keep). Its readers mark their reads optional in turn. A modification cannot be
    /// optional: what it reads must be there. Marking one, or a handle the pass has not
    /// declared, is [`GraphError::OptionalAccess`] when the graph compiles.
    pub fn optional<K: ResourceKind>(&mut self, handle: Handle<K>) -> &mut Self {
        let (id, version) = (handle.id, handle.version);
        let node = self.node();
        let mut marked = node
            .accesses
            .iter_mut()
            .filter(|a| a.resource == id && a.version == version)
            .peekable();
        let why = match marked.peek() {
            None => Some("the pass declared no access to it"),
            Some(_) => None,
        };
        let (mut reads, mut writes) = (false, false);
        for access in marked {
            reads |= access.role.reads();
            writes |= access.role.writes();
            access.optional = true;
        }
        let modifies = reads && writes;
        let why = why.or(modifies
            .then_some("the pass modifies it: only a read or a fresh write can be optional"));
        if let Some(why) = why {
            let pass = self.node().name.clone();
            let resource = self
                .graph
                .resources
                .get(id.index())
                .map_or_else(|| format!("{handle:?}"), |r| r.name.clone());
            self.graph.errors.push(GraphError::OptionalAccess {
                pass,
                resource,
                why: why.to_owned(),
            });
        }
        self
    }

    /// Keeps the pass even when nothing reads what it writes.
    pub fn side_effect(&mut self) -> &mut Self {
        self.node().side_effect = true;
        self
    }

    /// The declared resource behind a handle.
    pub fn resource<K: ResourceKind>(&self, handle: Handle<K>) -> &ResourceNode {
        self.graph.resource(handle)
    }

    /// Binds `target` as the next color attachment (locations count up from 0).
    pub fn color_output(&mut self, target: TextureHandle, load: ColorLoad) -> TextureHandle {
        let location = self.count(|r| matches!(r, TextureRole::Color { .. }));
        self.texture(target, TextureRole::Color { location, load })
    }

    /// Resolves the multisampled color attachment written as `color` (a handle this pass
    /// returned from [`color_output`](Self::color_output)) into `target` at the end of the pass.
    pub fn resolve_output(&mut self, color: TextureHandle, target: TextureHandle) -> TextureHandle {
        let location = self
            .node()
            .accesses
            .iter()
            .find_map(|a| match a.role {
                Role::Texture(TextureRole::Color { location, .. })
                    if a.resource == color.id && a.written == Some(color.version) =>
                {
                    Some(location)
                }
                _ => None,
            })
            .unwrap_or(u32::MAX);
        self.texture(target, TextureRole::Resolve { location })
    }

    /// Binds the depth-stencil attachment. Returns a new version when either aspect is
    /// written, else `target` itself. To sample the same texture in this pass, both
    /// aspects must be [`AspectAccess::ReadOnly`].
    ///
    /// An aspect the format lacks is declared `ReadOnly` (as wgpu's `None` ops) and
    /// recorded as [`AspectAccess::Absent`]: a depth prepass on `depth32float` clears depth
    /// without depending on stencil contents that do not exist.
    pub fn depth_stencil(
        &mut self,
        target: TextureHandle,
        depth: AspectAccess<f32>,
        stencil: AspectAccess<u32>,
    ) -> TextureHandle {
        let format = self
            .graph
            .resources
            .get(target.id.index())
            .and_then(ResourceNode::texture)
            .map(|desc| desc.format);
        let (depth, stencil) = match format {
            Some(f) => (
                absent_unless(depth, f.has_depth_aspect()),
                absent_unless(stencil, f.has_stencil_aspect()),
            ),
            None => (depth, stencil),
        };
        self.texture(target, TextureRole::DepthStencil { depth, stencil })
    }

    /// Binds a texture for sampling or `textureLoad` (multisampled textures included).
    pub fn sampled(&mut self, texture: TextureHandle) -> TextureHandle {
        self.sampled_aspect(texture, Aspect::All)
    }

    /// Binds one aspect of a depth-stencil texture for sampling.
    pub fn sampled_aspect(&mut self, texture: TextureHandle, aspect: Aspect) -> TextureHandle {
        self.texture(texture, TextureRole::Sampled { aspect })
    }

    /// Binds a storage texture that the pass only reads.
    pub fn storage_read(&mut self, texture: TextureHandle) -> TextureHandle {
        self.texture(
            texture,
            TextureRole::Storage {
                read: true,
                write: false,
            },
        )
    }

    /// Binds a storage texture that the pass overwrites without reading.
    pub fn storage_write(&mut self, texture: TextureHandle) -> TextureHandle {
        self.texture(
            texture,
            TextureRole::Storage {
                read: false,
                write: true,
            },
        )
    }

    /// Binds a storage texture that the pass reads and writes.
    pub fn storage_read_write(&mut self, texture: TextureHandle) -> TextureHandle {
        self.texture(
            texture,
            TextureRole::Storage {
                read: true,
                write: true,
            },
        )
    }

    /// A texture copied from.
    pub fn copy_src(&mut self, texture: TextureHandle) -> TextureHandle {
        self.texture(texture, TextureRole::CopySrc)
    }

    /// A texture copied into (its previous contents are not read).
    pub fn copy_dst(&mut self, texture: TextureHandle) -> TextureHandle {
        self.texture(texture, TextureRole::CopyDst)
    }

    /// A buffer accessed in `role`. Returns the new version when the role writes.
    pub fn buffer(&mut self, buffer: BufferHandle, role: BufferRole) -> BufferHandle {
        self.access(buffer, Role::Buffer(role))
    }

    /// Records the pass's commands. The render pass is already begun with the declared
    /// attachments and inferred load/store operations; the callback runs once per frame.
    #[cfg(feature = "gpu")]
    pub fn render(
        &mut self,
        record: impl FnMut(&mut crate::record::RenderContext<'_, '_>) + 'static,
    ) {
        self.node().record = Some(crate::record::Record::Render(Box::new(record)));
    }

    /// Records a compute pass's commands into the already begun compute pass.
    #[cfg(feature = "gpu")]
    pub fn compute(
        &mut self,
        record: impl FnMut(&mut crate::record::ComputeContext<'_, '_>) + 'static,
    ) {
        self.node().record = Some(crate::record::Record::Compute(Box::new(record)));
    }

    /// Records a transfer pass's commands into the command encoder.
    #[cfg(feature = "gpu")]
    pub fn transfer(
        &mut self,
        record: impl FnMut(&mut crate::record::TransferContext<'_>) + 'static,
    ) {
        self.node().record = Some(crate::record::Record::Transfer(Box::new(record)));
    }

    fn node(&mut self) -> &mut PassNode {
        &mut self.graph.passes[self.id.index()]
    }

    fn count(&mut self, pred: impl Fn(&TextureRole) -> bool) -> u32 {
        self.node()
            .accesses
            .iter()
            .filter(|a| matches!(a.role, Role::Texture(ref r) if pred(r)))
            .count() as u32
    }

    fn texture(&mut self, handle: Handle<Texture>, role: TextureRole) -> Handle<Texture> {
        self.access(handle, Role::Texture(role))
    }

    fn access<K: ResourceKind>(&mut self, handle: Handle<K>, role: Role) -> Handle<K> {
        // Handles carry no graph identity: one naming a resource or version this graph
        // never handed out is the detectable part of a handle from another graph.
        let resource = self
            .graph
            .resources
            .get_mut(handle.id.index())
            .filter(|r| handle.version < r.versions);
        let Some(resource) = resource else {
            let pass = self.node().name.clone();
            self.graph.errors.push(GraphError::ForeignHandle {
                pass,
                resource: format!("{handle:?}"),
            });
            return handle;
        };
        let written = role.writes().then(|| {
            resource.versions += 1;
            resource.versions - 1
        });
        self.node().accesses.push(Access {
            resource: handle.id,
            role,
            version: handle.version,
            written,
            optional: false,
        });
        Handle::new(handle.id, written.unwrap_or(handle.version))
    }
}

/// A read-only access to an aspect the format does not have is no access at all.
fn absent_unless<T>(access: AspectAccess<T>, present: bool) -> AspectAccess<T> {
    match access {
        AspectAccess::ReadOnly if !present => AspectAccess::Absent,
        other => other,
    }
}
