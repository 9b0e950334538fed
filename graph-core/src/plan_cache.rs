//! Plans cached by what decides them, so a scene change that keeps the features a graph
//! sees recompiles nothing.

use std::collections::HashMap;

use crate::compile::CompileOptions;
use crate::condition::Features;
use crate::graph::Graph;
use crate::plan::Plan;

/// A graph that compiles for a feature set: [`Graph`], or a
/// [`LoadedGraph`](crate::file::LoadedGraph), whose errors carry file positions. Sealed:
/// a [`CompiledGraph`](crate::CompiledGraph) relies on the graph it executes being the
/// graph it compiled.
pub trait Compile: sealed::Graphs {
    /// What a failed compile returns: [`GraphErrors`](crate::GraphErrors) for a
    /// [`Graph`], errors with file positions for a loaded graph file.
    type Error;

    /// See [`Graph::compile_for`].
    fn compile_for(
        &self,
        options: &CompileOptions,
        features: &Features,
    ) -> Result<Plan, Self::Error>;

    /// The features among `features` that the graph's conditions can see.
    fn relevant(&self, features: &Features) -> Features;
}

/// Reaching the declared graph inside what compiles, for the crate alone.
pub(crate) mod sealed {
    use crate::graph::Graph;

    pub trait Graphs {
        /// The graph that `compile_for` compiles.
        #[cfg(feature = "gpu")]
        fn graph_mut(&mut self) -> &mut Graph;
    }

    impl Graphs for Graph {
        #[cfg(feature = "gpu")]
        fn graph_mut(&mut self) -> &mut Graph {
            self
        }
    }
}

impl Compile for Graph {
    type Error = crate::error::GraphErrors;

    fn compile_for(
        &self,
        options: &CompileOptions,
        features: &Features,
    ) -> Result<Plan, Self::Error> {
        Graph::compile_for(self, options, features)
    }

    fn relevant(&self, features: &Features) -> Features {
        Graph::relevant(self, features)
    }
}

/// What a plan depends on besides its graph. Profiles are told apart by name, as
/// [`DeviceProfile`](crate::DeviceProfile)s are made for one device each; features are
/// the graph's relevant ones with the profile's device conditions, so undeclared
/// features do not split the cache and a plan's features find it again.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub(crate) struct PlanKey {
    pub features: Features,
    pub output_size: (u32, u32),
    pub profile: String,
}

/// Compiled plans of one graph by what decides them (the output size, the profile's
/// name and the features the graph declares among those asked for), with hit and miss
/// counts. Use one cache per graph: the key does not name the graph. Failed compiles are
/// not kept.
#[derive(Default)]
pub struct PlanCache {
    plans: HashMap<PlanKey, Plan>,
    hits: u64,
    misses: u64,
}

impl PlanCache {
    /// An empty cache.
    pub fn new() -> PlanCache {
        PlanCache::default()
    }

    /// The plan for `options` and `features`, compiled on the first request for its key.
    pub fn get_or_compile<G: Compile>(
        &mut self,
        graph: &G,
        options: &CompileOptions,
        features: &Features,
    ) -> Result<&Plan, G::Error> {
        let key = self.compile_key(graph, options, features)?;
        Ok(self.get(&key))
    }

    /// Compiles the plan for `options` and `features` unless it is held, and returns its
    /// key.
    pub(crate) fn compile_key<G: Compile>(
        &mut self,
        graph: &G,
        options: &CompileOptions,
        features: &Features,
    ) -> Result<PlanKey, G::Error> {
        // The features the compile reads: the device's conditions replace the caller's
        // (as `compile_for` has them), so a plan's own features ask for its key again.
        let key = PlanKey {
            features: graph.relevant(&options.profile.conditions(features)),
            output_size: options.output_size,
            profile: options.profile.name.clone(),
        };
        if self.plans.contains_key(&key) {
            self.hits += 1;
        } else {
            let plan = graph.compile_for(options, &key.features)?;
            self.misses += 1;
            self.plans.insert(key.clone(), plan);
        }
        Ok(key)
    }

    /// The plan of a key [`compile_key`](Self::compile_key) returned.
    pub(crate) fn get(&self, key: &PlanKey) -> &Plan {
        &self.plans[key]
    }

    /// Requests answered from the cache.
    pub fn hits(&self) -> u64 {
        self.hits
    }

    /// Requests that compiled (successfully).
    pub fn misses(&self) -> u64 {
        self.misses
    }

    /// Plans held.
    pub fn len(&self) -> usize {
        self.plans.len()
    }

    /// Whether no plan is held.
    pub fn is_empty(&self) -> bool {
        self.plans.is_empty()
    }
}
