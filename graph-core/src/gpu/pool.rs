//! Physical textures and buffers kept across frames.
//!
//! Each frame the executor acquires one object per physical texture and buffer of its
//! plan; an object acquired this frame is never handed out twice in it. Objects are keyed
//! by exactly what wgpu creates them from, so a plan executed again reuses every texture,
//! view and buffer and creates none. (Bind groups are not pooled: pass callbacks create
//! theirs each frame, small descriptor objects pointing at this memory.) Objects no frame has used for [`KEEP_FRAMES`] frames are dropped
//! (wgpu frees the memory once the GPU is done with them).

use std::collections::HashMap;

use wgpu::{BufferUsages, TextureUsages};

use super::error_scopes::ErrorScopes;
use crate::access::Aspect;
use crate::resource::TextureShape;

/// Frames an unused object survives before it is freed: long enough to ride out a frame
/// that skips a pass, short enough that a resize does not keep both sizes for long.
pub const KEEP_FRAMES: u64 = 3;

/// Allocation counters, for tests and memory reports.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub struct PoolStats {
    /// Textures created since the pool was made.
    pub textures_allocated: u64,
    /// Buffers created since the pool was made.
    pub buffers_allocated: u64,
    /// Textures created by the current (last begun) frame.
    pub frame_textures_allocated: u32,
    /// Buffers created by the current (last begun) frame.
    pub frame_buffers_allocated: u32,
    /// Textures alive in the pool now.
    pub textures_alive: usize,
    /// Buffers alive in the pool now.
    pub buffers_alive: usize,
}

/// Which view of a pooled texture: what a sampled binding asks for, or the single-mip,
/// single-layer view a render attachment needs.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub(crate) enum ViewKey {
    Aspect(Aspect),
    Attachment,
}

struct PooledTexture {
    key: (TextureShape, TextureUsages),
    texture: wgpu::Texture,
    /// Views are made once per texture, not per frame.
    views: HashMap<ViewKey, wgpu::TextureView>,
    last_used: u64,
}

struct PooledBuffer {
    key: (u64, BufferUsages),
    buffer: wgpu::Buffer,
    last_used: u64,
}

/// The pool. Indices it returns are valid until the next [`Pool::begin_frame`].
#[derive(Default)]
pub(crate) struct Pool {
    textures: Vec<PooledTexture>,
    buffers: Vec<PooledBuffer>,
    /// Starts at 1 after the first `begin_frame`, so `last_used == 0` means never.
    frame: u64,
    stats: PoolStats,
}

impl Pool {
    /// Starts a frame: everything becomes available again, and what has been idle for
    /// [`KEEP_FRAMES`] frames is dropped.
    pub fn begin_frame(&mut self) {
        self.frame += 1;
        let frame = self.frame;
        self.textures.retain(|t| frame - t.last_used <= KEEP_FRAMES);
        self.buffers.retain(|b| frame - b.last_used <= KEEP_FRAMES);
        self.stats.frame_textures_allocated = 0;
        self.stats.frame_buffers_allocated = 0;
        self.update_alive();
    }

    /// A texture of this shape and usage that no one else holds this frame; `label` names
    /// it if it has to be created. When creating it fails (out of memory, or beyond what
    /// the device allows), the error is wgpu's message and the pool keeps nothing.
    pub fn acquire_texture(
        &mut self,
        device: &wgpu::Device,
        shape: TextureShape,
        usage: TextureUsages,
        label: impl FnOnce() -> String,
    ) -> Result<usize, String> {
        let key = (shape, usage);
        let frame = self.frame;
        if let Some(i) = self
            .textures
            .iter()
            .position(|t| t.key == key && t.last_used != frame)
        {
            self.textures[i].last_used = frame;
            return Ok(i);
        }
        let scopes = ErrorScopes::push(device);
        let texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some(&label()),
            size: wgpu::Extent3d {
                width: shape.width,
                height: shape.height,
                depth_or_array_layers: shape.layers,
            },
            mip_level_count: shape.mips,
            sample_count: shape.samples,
            dimension: wgpu::TextureDimension::D2,
            format: shape.format,
            usage,
            view_formats: &[],
        });
        if let Some(error) = scopes.pop() {
            return Err(error);
        }
        self.textures.push(PooledTexture {
            key,
            texture,
            views: HashMap::new(),
            last_used: frame,
        });
        self.stats.textures_allocated += 1;
        self.stats.frame_textures_allocated += 1;
        self.update_alive();
        Ok(self.textures.len() - 1)
    }

    /// A buffer of this size and usage that no one else holds this frame. Failures as
    /// for [`Pool::acquire_texture`].
    pub fn acquire_buffer(
        &mut self,
        device: &wgpu::Device,
        size: u64,
        usage: BufferUsages,
        label: impl FnOnce() -> String,
    ) -> Result<usize, String> {
        let key = (size, usage);
        let frame = self.frame;
        if let Some(i) = self
            .buffers
            .iter()
            .position(|b| b.key == key && b.last_used != frame)
        {
            self.buffers[i].last_used = frame;
            return Ok(i);
        }
        let scopes = ErrorScopes::push(device);
        let buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(&label()),
            size,
            usage,
            mapped_at_creation: false,
        });
        if let Some(error) = scopes.pop() {
            return Err(error);
        }
        self.buffers.push(PooledBuffer {
            key,
            buffer,
            last_used: frame,
        });
        self.stats.buffers_allocated += 1;
        self.stats.frame_buffers_allocated += 1;
        self.update_alive();
        Ok(self.buffers.len() - 1)
    }

    pub fn texture(&self, index: usize) -> &wgpu::Texture {
        &self.textures[index].texture
    }

    pub fn buffer(&self, index: usize) -> &wgpu::Buffer {
        &self.buffers[index].buffer
    }

    /// A view of a pooled texture, made on first use and kept with the texture.
    pub fn view(&mut self, index: usize, key: ViewKey) -> wgpu::TextureView {
        let pooled = &mut self.textures[index];
        pooled
            .views
            .entry(key)
            .or_insert_with(|| make_view(&pooled.texture, key))
            .clone()
    }

    pub fn stats(&self) -> PoolStats {
        self.stats
    }

    fn update_alive(&mut self) {
        self.stats.textures_alive = self.textures.len();
        self.stats.buffers_alive = self.buffers.len();
    }
}

/// Makes the view `key` names. Attachments see mip 0 and layer 0 only, because a render
/// pass attaches a single subresource; everything else sees the whole texture.
pub(crate) fn make_view(texture: &wgpu::Texture, key: ViewKey) -> wgpu::TextureView {
    let desc = match key {
        ViewKey::Aspect(aspect) => wgpu::TextureViewDescriptor {
            label: None,
            aspect: match aspect {
                Aspect::All => wgpu::TextureAspect::All,
                Aspect::DepthOnly => wgpu::TextureAspect::DepthOnly,
                Aspect::StencilOnly => wgpu::TextureAspect::StencilOnly,
            },
            ..Default::default()
        },
        ViewKey::Attachment => wgpu::TextureViewDescriptor {
            label: None,
            dimension: Some(wgpu::TextureViewDimension::D2),
            mip_level_count: Some(1),
            array_layer_count: Some(1),
            ..Default::default()
        },
    };
    texture.create_view(&desc)
}
