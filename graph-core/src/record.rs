//! Recording a pass (feature `gpu`): the callback a pass declares ([`Record`]) and what it
//! sees when the executor calls it, the begun wgpu pass (or encoder) and the frame's
//! physical resources, looked up through the handles the pass declared. Declaring a pass
//! needs these types, so they belong with the model, below compile and execution; the
//! executor fills them in.
//!
//! Views and buffers borrowed from a context are valid for this frame only: the pool may
//! hand the same memory to another resource in another pass. Device objects a callback
//! creates (pipelines, samplers) are the callback's own to keep across frames.

use std::collections::HashMap;

use crate::access::{Access, Aspect, DroppedRead, Role, TextureRole};
use crate::handle::{BufferHandle, Handle, ResourceId, ResourceKind, TextureHandle};
use crate::resource::{ResourceNode, TextureShape};

/// The callback that records a pass's commands. It runs once per executed frame, so it
/// may keep pipelines and other device objects it creates on the first call.
pub enum Record {
    /// Records into the render pass the executor began with the pass's attachments.
    Render(Box<dyn FnMut(&mut RenderContext<'_, '_>)>),
    /// Records into the compute pass the executor began.
    Compute(Box<dyn FnMut(&mut ComputeContext<'_, '_>)>),
    /// Records into the frame's command encoder (copies).
    Transfer(Box<dyn FnMut(&mut TransferContext<'_>)>),
}

/// This frame's objects by resource, for every resource a live pass accesses: owned
/// (cheap reference-counted clones), so that [`FrameResources`] can borrow them while the
/// executor's own fields stay borrowable.
#[derive(Default)]
pub(crate) struct FrameObjects {
    pub textures: HashMap<ResourceId, (wgpu::Texture, TextureShape)>,
    /// Views for callbacks: every texture's full view, and the sampled aspects declared.
    pub views: HashMap<(ResourceId, Aspect), wgpu::TextureView>,
    /// Views the executor attaches to render passes.
    pub attachments: HashMap<ResourceId, wgpu::TextureView>,
    pub buffers: HashMap<ResourceId, wgpu::Buffer>,
    /// The history resources that read zeros this frame rather than a frame's contents.
    pub resets: std::collections::HashSet<ResourceId>,
}

/// The physical resources of one executing frame, as one pass sees them.
///
/// Lookups are checked against the executing pass's declared accesses (less the optional
/// reads its plan leaves out, see [`has`](Self::has)), as Filament's
/// frame graph asserts: a handle the pass did not declare, or declared at another
/// version, is a bug in the pass (the graph ordered and allocated the frame from the
/// declarations, so an undeclared resource may hold anything, or another resource's
/// data, at that point). Each lookup accepts the version a declared access was handed
/// and the version it produced, and panics with a message naming the pass, the resource
/// and the version otherwise.
pub struct FrameResources<'f> {
    /// The device, for creating what the pass keeps (pipelines, samplers) and this frame's
    /// bind groups.
    pub device: &'f wgpu::Device,
    /// The queue, for writing the pass's own buffers before the frame is submitted.
    pub queue: &'f wgpu::Queue,
    pub(crate) output_size: (u32, u32),
    pub(crate) objects: &'f FrameObjects,
    /// The executing pass.
    pub(crate) pass: &'f str,
    /// What the executing pass declared.
    pub(crate) accesses: &'f [Access],
    /// The optional reads (and fresh writes) of the executing pass that its plan leaves
    /// out.
    pub(crate) dropped: &'f [DroppedRead],
    /// Every resource of the graph, by id: their names, for messages.
    pub(crate) resources: &'f [ResourceNode],
    /// Why the executing pass could not record its work, when its callback said so.
    pub(crate) failure: &'f std::cell::RefCell<Option<String>>,
    /// Bytes of the buffers the executing pass keeps for itself ([`Self::hold`]).
    pub(crate) held: &'f std::cell::Cell<u64>,
    /// The frame's number ([`Self::frame`]).
    pub(crate) frame: u64,
}

impl<'f> FrameResources<'f> {
    /// Counts `buffer`, which the executing pass made and keeps for itself (a rasteriser's
    /// bins, a list of pixels), in this frame's [`PassTiming::held_bytes`]: memory the
    /// plan does not know of, which reports of a frame's memory add. The pass still owns
    /// the buffer; call it each frame for each such buffer the frame uses.
    ///
    /// [`PassTiming::held_bytes`]: crate::gpu::PassTiming::held_bytes
    pub fn hold(&self, buffer: &wgpu::Buffer) {
        self.held.set(self.held.get() + buffer.size());
    }

    /// How many frames the executor began before this one (0 for its first): every pass
    /// of a frame sees the same number, and each frame a greater one, so a pass can tell
    /// a new frame from another recording of the same one (a temporal technique's
    /// per-frame jitter, the previous frame's inputs).
    pub fn frame(&self) -> u64 {
        self.frame
    }

    /// The size relative textures were resolved against.
    pub fn output_size(&self) -> (u32, u32) {
        self.output_size
    }

    /// Says that the executing pass cannot record its work on this device, and why (`why`
    /// names what the device lacks: "the scene's 3 GiB of vertices exceed the storage
    /// binding limit of 2 GiB", say): the frame fails with [`ExecuteError::Pass`] naming
    /// the pass, and nothing of it is submitted. The callback should then return without
    /// recording; a second call keeps the first reason.
    ///
    /// [`ExecuteError::Pass`]: crate::gpu::ExecuteError::Pass
    pub fn fail(&self, why: impl Into<String>) {
        self.failure.borrow_mut().get_or_insert_with(|| why.into());
    }

    /// The texture behind a handle.
    ///
    /// # Panics
    /// When the executing pass did not declare an access to this version of the texture.
    pub fn texture(&self, handle: TextureHandle) -> &'f wgpu::Texture {
        self.check(handle, "texture", None);
        &self.objects.textures[&handle.id()].0
    }

    /// Format, size and sample count of a texture, as planned.
    ///
    /// # Panics
    /// As [`texture`](Self::texture).
    pub fn shape(&self, handle: TextureHandle) -> TextureShape {
        self.check(handle, "texture", None);
        self.objects.textures[&handle.id()].1
    }

    /// The full view of a texture.
    ///
    /// # Panics
    /// As [`texture`](Self::texture).
    pub fn view(&self, handle: TextureHandle) -> &'f wgpu::TextureView {
        self.aspect_view(handle, Aspect::All)
    }

    /// A view of one aspect. [`Aspect::All`] is the full view of any declared texture;
    /// a single aspect needs the pass to have declared `sampled_aspect(handle, aspect)`.
    ///
    /// # Panics
    /// When the executing pass did not declare this version of the texture, or declared
    /// no sampled access to the aspect asked for.
    pub fn aspect_view(&self, handle: TextureHandle, aspect: Aspect) -> &'f wgpu::TextureView {
        let needs = (aspect != Aspect::All).then_some(aspect);
        self.check(handle, "texture", needs);
        &self.objects.views[&(handle.id(), aspect)]
    }

    /// Whether the history `history` (a handle of a resource declared with
    /// [`GraphBuilder::history_texture`](crate::GraphBuilder::history_texture) or as
    /// `History(of: ..)` in a file) holds zeros this frame rather than the previous
    /// frame's contents: true on the first frame, and the first after a resize, a change
    /// of plan or [`Executor::reset_history`](crate::gpu::Executor::reset_history). A
    /// temporal filter then takes this frame's value alone.
    ///
    /// # Panics
    /// When the executing pass did not declare this version of the texture, or the
    /// texture is not a history.
    pub fn history_reset(&self, history: TextureHandle) -> bool {
        self.check(history, "texture", None);
        let resource = &self.resources[history.id().index()];
        if resource.origin.history_of().is_none() {
            panic!(
                "pass \"{}\" asked whether \"{}\" was reset, but it is not a history",
                self.pass, resource.name
            );
        }
        self.objects.resets.contains(&history.id())
    }

    /// Whether the executing pass can look `handle` up this frame: false for an optional
    /// read ([`PassBuilder::optional`](crate::PassBuilder::optional)) that the plan
    /// leaves out because a condition dropped its resource or writer, and for what the
    /// pass never declared. A pass with an optional input asks this before it builds
    /// pipelines that bind the input; the answer holds for every frame of one plan.
    pub fn has<K: ResourceKind>(&self, handle: Handle<K>) -> bool {
        self.declared(handle, "resource", None).is_ok()
    }

    /// The buffer behind a handle.
    ///
    /// # Panics
    /// When the executing pass did not declare an access to this version of the buffer.
    pub fn buffer(&self, handle: BufferHandle) -> &'f wgpu::Buffer {
        self.check(handle, "buffer", None);
        &self.objects.buffers[&handle.id()]
    }

    /// Panics unless the executing pass declared `handle` (as a sampled view of `aspect`,
    /// when given) at the handle's version.
    fn check<K: ResourceKind>(
        &self,
        handle: Handle<K>,
        kind: &'static str,
        aspect: Option<Aspect>,
    ) {
        if let Err(e) = self.declared(handle, kind, aspect) {
            panic!("{e}");
        }
    }

    fn declared<K: ResourceKind>(
        &self,
        handle: Handle<K>,
        kind: &'static str,
        aspect: Option<Aspect>,
    ) -> Result<(), UndeclaredAccess> {
        let (id, version) = (handle.id(), handle.version());
        let of_resource = || {
            self.accesses
                .iter()
                .filter(move |a| a.resource == id && !self.dropped.iter().any(|d| d.covers(a)))
        };
        let found = of_resource()
            .filter(|a| a.version == version || a.written == Some(version))
            .any(|a| match aspect {
                None => true,
                Some(aspect) => a.role == Role::Texture(TextureRole::Sampled { aspect }),
            });
        if found {
            return Ok(());
        }
        let declared: Vec<String> = of_resource()
            .map(|a| match a.written {
                Some(written) if a.role.reads() => {
                    format!("{} (version {} to {written})", describe(a), a.version)
                }
                Some(written) => format!("{} (version {written})", describe(a)),
                None => format!("{} (version {})", describe(a), a.version),
            })
            .collect();
        Err(UndeclaredAccess {
            pass: self.pass.to_string(),
            what: match aspect {
                Some(Aspect::DepthOnly) => "the depth view of texture",
                Some(Aspect::StencilOnly) => "the stencil view of texture",
                Some(Aspect::All) | None => kind,
            },
            resource: self
                .resources
                .get(id.index())
                .map_or_else(|| format!("#{}", id.0), |r| r.name.clone()),
            version,
            declared: match (declared.is_empty(), self.dropped_read(id, version)) {
                (_, Some(why)) => format!(
                    "an optional access its plan leaves out ({why}): ask `has` before \
                     looking it up"
                ),
                (true, None) => "which it did not declare".to_owned(),
                (false, None) => format!(
                    "which it did not declare (it declared it as {})",
                    declared.join(", ")
                ),
            },
        })
    }

    /// Why the plan leaves out the executing pass's optional read of this version, if it
    /// does.
    fn dropped_read(&self, id: ResourceId, version: u32) -> Option<&str> {
        let dropped = self.dropped.iter();
        dropped
            .filter(|d| d.resource == id && d.version == version)
            .map(|d| d.why.as_str())
            .next()
    }
}

/// A role and, for sampled textures, the aspect: "sampled texture (depth)".
fn describe(access: &Access) -> String {
    match access.role {
        Role::Texture(TextureRole::Sampled {
            aspect: aspect @ (Aspect::DepthOnly | Aspect::StencilOnly),
        }) => format!(
            "{} ({})",
            access.role.describe(),
            match aspect {
                Aspect::DepthOnly => "depth",
                _ => "stencil",
            }
        ),
        role => role.describe().to_string(),
    }
}

/// A record callback looked up what its pass did not declare: the message of the panic.
#[derive(Debug, thiserror::Error)]
#[error("pass \"{pass}\" looked up {what} \"{resource}\" (version {version}), {declared}")]
struct UndeclaredAccess {
    pass: String,
    /// "texture", "buffer", "the depth view of texture".
    what: &'static str,
    resource: String,
    version: u32,
    /// Why that is wrong: "which it did not declare", with what the pass did declare of
    /// the resource, if anything, or that the plan leaves the read out.
    declared: String,
}

/// A render pass callback's view of the frame: the render pass, begun with the declared
/// attachments, and the frame's resources as the pass declared them.
pub struct RenderContext<'a, 'p> {
    /// The begun render pass: attachments bound, viewport the attachments' size.
    pub pass: &'a mut wgpu::RenderPass<'p>,
    /// The frame's resources, as this pass declared them.
    pub resources: &'a FrameResources<'a>,
}

/// A compute pass callback's view of the frame.
pub struct ComputeContext<'a, 'p> {
    /// The begun compute pass.
    pub pass: &'a mut wgpu::ComputePass<'p>,
    /// The frame's resources, as this pass declared them.
    pub resources: &'a FrameResources<'a>,
}

/// A transfer pass callback's view of the frame: the command encoder itself.
pub struct TransferContext<'a> {
    /// The frame's command encoder, between the passes before and after this one.
    pub encoder: &'a mut wgpu::CommandEncoder,
    /// The frame's resources, as this pass declared them.
    pub resources: &'a FrameResources<'a>,
}
