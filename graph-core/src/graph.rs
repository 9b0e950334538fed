//! A declared graph, ready to compile.

use crate::condition::Features;
use crate::error::GraphError;
use crate::handle::{Handle, ResourceKind};
use crate::pass::PassNode;
use crate::resource::ResourceNode;

/// A graph whose passes and resources are all declared. Compiling it needs no GPU and
/// does not consume it: the same graph can be compiled for several output sizes or
/// device profiles. To execute it, bind it to its plans in a
/// [`CompiledGraph`](crate::CompiledGraph).
pub struct Graph {
    pub(crate) resources: Vec<ResourceNode>,
    pub(crate) passes: Vec<PassNode>,
    /// The feature names conditions may use.
    pub(crate) features: Features,
    /// Mistakes found while declaring, reported by the first compile.
    pub(crate) declare_errors: Vec<GraphError>,
}

impl Graph {
    /// Every declared resource, indexed by [`ResourceId::index`](crate::ResourceId::index).
    pub fn resources(&self) -> &[ResourceNode] {
        &self.resources
    }

    /// Every declared pass in declaration order, indexed by
    /// [`PassId::index`](crate::PassId::index); the plan's order is the compiler's.
    pub fn passes(&self) -> &[PassNode] {
        &self.passes
    }

    /// The feature names the graph's conditions may use.
    pub fn declared_features(&self) -> &Features {
        &self.features
    }

    /// The part of `features` this graph's conditions can see: plans for feature sets
    /// that differ only in undeclared features are the same plan.
    pub fn relevant(&self, features: &Features) -> Features {
        features.intersection(&self.features)
    }

    /// Feature sets that between them keep every pass and resource in the graph: none,
    /// and for each distinct condition the features it requires. Compiling for each
    /// validates what any single feature set would drop.
    pub fn witnesses(&self) -> Vec<Features> {
        let conditions = self
            .passes
            .iter()
            .map(|p| &p.condition)
            .chain(self.resources.iter().map(|r| &r.condition));
        let mut sets = vec![Features::new()];
        for condition in conditions.flatten() {
            let witness = condition.witness();
            if !sets.contains(&witness) {
                sets.push(witness);
            }
        }
        sets
    }

    /// The declared resource behind a handle.
    ///
    /// # Panics
    /// When the handle comes from another graph with more resources.
    pub fn resource<K: ResourceKind>(&self, handle: Handle<K>) -> &ResourceNode {
        &self.resources[handle.id().index()]
    }

    /// The id of the resource called `name` (the first, if names repeat).
    pub fn resource_id(&self, name: &str) -> Option<crate::handle::ResourceId> {
        self.resources
            .iter()
            .position(|r| r.name == name)
            .map(|i| crate::handle::ResourceId(i as u32))
    }
}
