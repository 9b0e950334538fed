//! Typed, versioned handles: the only way code names a resource or a pass.

use std::fmt;
use std::hash::{Hash, Hasher};
use std::marker::PhantomData;

/// Index of a resource in its graph. Stable for the life of the graph.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, serde::Serialize)]
pub struct ResourceId(pub u32);

/// Index of a pass in declaration order.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, serde::Serialize)]
pub struct PassId(pub u32);

impl ResourceId {
    /// The index into [`Graph::resources`](crate::Graph::resources) and
    /// [`Plan::resources`](crate::Plan::resources).
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

impl PassId {
    /// The index into [`Graph::passes`](crate::Graph::passes).
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

/// Marker for texture handles.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub enum Texture {}
/// Marker for buffer handles.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub enum Buffer {}

/// A resource kind: what a [`Handle`] may point at.
pub trait ResourceKind: Copy + 'static {
    /// The kind as a value, for messages and checks at run time.
    const KIND: Kind;
}
impl ResourceKind for Texture {
    const KIND: Kind = Kind::Texture;
}
impl ResourceKind for Buffer {
    const KIND: Kind = Kind::Buffer;
}

/// The kind of a resource, as data.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Kind {
    /// A texture.
    Texture,
    /// A buffer.
    Buffer,
}

/// One version of one resource.
///
/// Every write returns a new handle whose version is one higher; the handle it was
/// given stays usable for reads of the older contents (which orders those reads before
/// the write). Writing through a handle that another pass already wrote through is a
/// compile error that names both passes: a version has exactly one writer.
pub struct Handle<K: ResourceKind> {
    pub(crate) id: ResourceId,
    pub(crate) version: u32,
    marker: PhantomData<K>,
}

/// A version of a texture.
pub type TextureHandle = Handle<Texture>;
/// A version of a buffer.
pub type BufferHandle = Handle<Buffer>;

impl<K: ResourceKind> Handle<K> {
    pub(crate) fn new(id: ResourceId, version: u32) -> Self {
        Self {
            id,
            version,
            marker: PhantomData,
        }
    }

    /// The resource this handle points at, whatever its version.
    pub fn id(&self) -> ResourceId {
        self.id
    }

    /// The version: 0 is the contents before any pass of the graph wrote it.
    pub fn version(&self) -> u32 {
        self.version
    }
}

// Manual impls: derives would require `K: Clone` etc. on the uninhabited markers.
impl<K: ResourceKind> Clone for Handle<K> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<K: ResourceKind> Copy for Handle<K> {}
impl<K: ResourceKind> PartialEq for Handle<K> {
    fn eq(&self, other: &Self) -> bool {
        self.id == other.id && self.version == other.version
    }
}
impl<K: ResourceKind> Eq for Handle<K> {}
impl<K: ResourceKind> Hash for Handle<K> {
    fn hash<H: Hasher>(&self, state: &mut H) {
        self.id.hash(state);
        self.version.hash(state);
    }
}
impl<K: ResourceKind> fmt::Debug for Handle<K> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:?}#{}@v{}", K::KIND, self.id.0, self.version)
    }
}
