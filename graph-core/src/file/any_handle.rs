//! A handle whose kind is known only at run time: what a name in a graph file stands for.

use crate::handle::{BufferHandle, Handle, Kind, ResourceId, ResourceKind, TextureHandle};

/// A texture or buffer handle.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub enum AnyHandle {
    /// A texture version.
    Texture(TextureHandle),
    /// A buffer version.
    Buffer(BufferHandle),
}

impl AnyHandle {
    /// Texture or buffer.
    pub fn kind(&self) -> Kind {
        match self {
            AnyHandle::Texture(_) => Kind::Texture,
            AnyHandle::Buffer(_) => Kind::Buffer,
        }
    }

    /// The resource, whatever its version ([`Handle::id`]).
    pub fn id(&self) -> ResourceId {
        match self {
            AnyHandle::Texture(h) => h.id(),
            AnyHandle::Buffer(h) => h.id(),
        }
    }

    /// The version ([`Handle::version`]).
    pub fn version(&self) -> u32 {
        match self {
            AnyHandle::Texture(h) => h.version(),
            AnyHandle::Buffer(h) => h.version(),
        }
    }

    /// The typed handle, when the kind is `K`.
    pub fn typed<K: ResourceKind>(&self) -> Option<Handle<K>> {
        (self.kind() == K::KIND).then(|| Handle::new(self.id(), self.version()))
    }
}

impl<K: ResourceKind> From<Handle<K>> for AnyHandle {
    fn from(handle: Handle<K>) -> Self {
        let (id, version) = (handle.id(), handle.version());
        match K::KIND {
            Kind::Texture => AnyHandle::Texture(Handle::new(id, version)),
            Kind::Buffer => AnyHandle::Buffer(Handle::new(id, version)),
        }
    }
}
