//! What a pass's record callback sees: the begun wgpu pass (or encoder) and the frame's
//! physical resources, looked up through the same handles the pass declared.
//!
//! Views and buffers borrowed from a context are valid for this frame only: the pool may
//! hand the same memory to another resource in another pass. Device objects a callback
//! creates (pipelines, samplers) are the callback's own to keep across frames.

use std::collections::HashMap;

use crate::access::Aspect;
use crate::handle::{BufferHandle, ResourceId, TextureHandle};
use crate::plan::TextureShape;

/// The physical resources of one executing frame.
pub struct FrameResources<'f> {
    pub device: &'f wgpu::Device,
    pub queue: &'f wgpu::Queue,
    pub(crate) output_size: (u32, u32),
    pub(crate) textures: HashMap<ResourceId, (&'f wgpu::Texture, TextureShape)>,
    pub(crate) views: HashMap<(ResourceId, Aspect), &'f wgpu::TextureView>,
    pub(crate) buffers: HashMap<ResourceId, &'f wgpu::Buffer>,
}

impl<'f> FrameResources<'f> {
    /// The size relative textures were resolved against.
    pub fn output_size(&self) -> (u32, u32) {
        self.output_size
    }

    /// The texture behind a handle. Panics only if the handle was not declared by the
    /// executing graph, which compile already rejects.
    pub fn texture(&self, handle: TextureHandle) -> &'f wgpu::Texture {
        self.textures[&handle.id()].0
    }

    /// Format, size and sample count of a texture, as planned.
    pub fn shape(&self, handle: TextureHandle) -> TextureShape {
        self.textures[&handle.id()].1
    }

    /// The full view of a texture.
    pub fn view(&self, handle: TextureHandle) -> &'f wgpu::TextureView {
        self.aspect_view(handle, Aspect::All)
    }

    /// A view of one aspect, for passes that declared `sampled_aspect(handle, aspect)`.
    pub fn aspect_view(&self, handle: TextureHandle, aspect: Aspect) -> &'f wgpu::TextureView {
        self.views[&(handle.id(), aspect)]
    }

    pub fn buffer(&self, handle: BufferHandle) -> &'f wgpu::Buffer {
        self.buffers[&handle.id()]
    }
}

/// A render pass callback's view of the frame: the render pass, begun with the declared
/// attachments, and the frame's resources.
pub struct RenderContext<'a, 'p> {
    pub pass: &'a mut wgpu::RenderPass<'p>,
    pub resources: &'a FrameResources<'a>,
}

/// A compute pass callback's view of the frame.
pub struct ComputeContext<'a, 'p> {
    pub pass: &'a mut wgpu::ComputePass<'p>,
    pub resources: &'a FrameResources<'a>,
}

/// A transfer pass callback's view of the frame: the command encoder itself.
pub struct TransferContext<'a> {
    pub encoder: &'a mut wgpu::CommandEncoder,
    pub resources: &'a FrameResources<'a>,
}
