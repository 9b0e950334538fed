//! A declared graph, ready to compile.

use crate::error::GraphError;
use crate::handle::{Handle, ResourceKind};
use crate::pass::PassNode;
use crate::resource::ResourceNode;

/// A graph whose passes and resources are all declared. Compiling it needs no GPU and
/// does not consume it: the same graph can be compiled for several output sizes or
/// device profiles, and executed with any plan compiled from it.
pub struct Graph {
    pub(crate) resources: Vec<ResourceNode>,
    pub(crate) passes: Vec<PassNode>,
    /// Mistakes found while declaring, reported by the first compile.
    pub(crate) declare_errors: Vec<GraphError>,
}

impl Graph {
    pub(crate) fn from_builder(builder: crate::GraphBuilder) -> Self {
        Self {
            resources: builder.resources,
            passes: builder.passes,
            declare_errors: builder.errors,
        }
    }

    pub fn resources(&self) -> &[ResourceNode] {
        &self.resources
    }

    pub fn passes(&self) -> &[PassNode] {
        &self.passes
    }

    pub fn resource<K: ResourceKind>(&self, handle: Handle<K>) -> &ResourceNode {
        &self.resources[handle.id().index()]
    }

    /// The id of the resource called `name` (the first, if names repeat).
    pub fn resource_id(&self, name: &str) -> Option<crate::ResourceId> {
        self.resources
            .iter()
            .position(|r| r.name == name)
            .map(|i| crate::ResourceId(i as u32))
    }
}
