//! A graph bound to the plans compiled from it: what the executor runs, so that a plan
//! can only ever be executed with the graph it was compiled from.

use crate::compile::CompileOptions;
use crate::condition::Features;
use crate::graph::Graph;
use crate::plan::Plan;
use crate::plan_cache::{Compile, PlanCache, PlanKey};

/// A graph ([`Graph`], or a [`LoadedGraph`](crate::file::LoadedGraph)) together with the
/// plan compiled from it. It is the only thing
/// [`Executor::execute`](crate::gpu::Executor::execute) runs, and the plan inside cannot be
/// replaced by one compiled from another graph: mismatched plans do not compile, where
/// they once failed at run time. As in Filament's frame graph, compile and execute happen
/// on one object.
///
/// The graph stays readable ([`graph`](Self::graph)) but cannot change while it is bound,
/// since a change would invalidate its plans; [`into_graph`](Self::into_graph) gives it
/// back. [`recompile`](Self::recompile) moves to the plan of other options or features
/// (a new output size, another scene's features), keeping every plan compiled so far in a
/// [`PlanCache`], so going back to one recompiles nothing.
///
/// ```no_run
/// # use rgraph_core::{CompileOptions, CompiledGraph, GraphBuilder};
/// # use rgraph_core::gpu::{AdapterChoice, Executor, Gpu, Imports};
/// # let gpu = Gpu::open(&AdapterChoice::from_env()).unwrap();
/// # let mut executor = Executor::new(&gpu);
/// let graph_a = GraphBuilder::new().build();
/// let mut compiled_a = CompiledGraph::new(graph_a, &CompileOptions::default()).unwrap();
/// executor.execute(&mut compiled_a, &Imports::new()).unwrap();
/// ```
///
/// A plan cannot be executed with another graph: there is no way to pass one.
///
/// ```compile_fail
/// # use rgraph_core::{CompileOptions, CompiledGraph, GraphBuilder};
/// # use rgraph_core::gpu::{AdapterChoice, Executor, Gpu, Imports};
/// # let gpu = Gpu::open(&AdapterChoice::from_env()).unwrap();
/// # let mut executor = Executor::new(&gpu);
/// let graph_a = GraphBuilder::new().build();
/// let mut graph_b = GraphBuilder::new().build();
/// let compiled_a = CompiledGraph::new(graph_a, &CompileOptions::default()).unwrap();
/// executor.execute(&mut graph_b, compiled_a.plan(), &Imports::new()).unwrap();
/// ```
///
/// Nor can another graph take the place of the one a plan was compiled from:
///
/// ```compile_fail
/// # use rgraph_core::{CompileOptions, CompiledGraph, GraphBuilder};
/// let graph_a = GraphBuilder::new().build();
/// let graph_b = GraphBuilder::new().build();
/// let mut compiled_a = CompiledGraph::new(graph_a, &CompileOptions::default()).unwrap();
/// compiled_a.graph = graph_b;
/// ```
pub struct CompiledGraph<G: Compile = Graph> {
    graph: G,
    plans: PlanCache,
    /// The key of the current plan, which `plans` holds.
    current: PlanKey,
}

impl<G: Compile> CompiledGraph<G> {
    /// Compiles `graph` for `options` with no feature set (see [`Graph::compile`]) and
    /// binds the two. On error the graph is dropped with the errors returned.
    pub fn new(graph: G, options: &CompileOptions) -> Result<Self, G::Error> {
        Self::new_for(graph, options, &Features::new())
    }

    /// Compiles `graph` for `options` and `features` (see [`Graph::compile_for`]) and
    /// binds the two. On error the graph is dropped with the errors returned.
    pub fn new_for(
        graph: G,
        options: &CompileOptions,
        features: &Features,
    ) -> Result<Self, G::Error> {
        let mut plans = PlanCache::new();
        let current = plans.compile_key(&graph, options, features)?;
        Ok(Self {
            graph,
            plans,
            current,
        })
    }

    /// Makes the plan for `options` and `features` the current one, compiling it unless
    /// an earlier call (or [`new_for`](Self::new_for)) already did. On error the current
    /// plan stays as it was.
    pub fn recompile(
        &mut self,
        options: &CompileOptions,
        features: &Features,
    ) -> Result<&Plan, G::Error> {
        self.current = self.plans.compile_key(&self.graph, options, features)?;
        Ok(self.plan())
    }

    /// The current plan: what the next execution runs.
    pub fn plan(&self) -> &Plan {
        self.plans.get(&self.current)
    }

    /// The graph the plans were compiled from.
    pub fn graph(&self) -> &G {
        &self.graph
    }

    /// The plans compiled so far, with their hit and miss counts.
    pub fn plans(&self) -> &PlanCache {
        &self.plans
    }

    /// Unbinds the graph, dropping its plans, so that it can be changed and compiled again.
    pub fn into_graph(self) -> G {
        self.graph
    }

    /// The declared graph, whose record callbacks the executor calls, and the current
    /// plan: borrowed together, so they are always the pair that belongs together.
    #[cfg(feature = "gpu")]
    pub(crate) fn parts(&mut self) -> (&mut Graph, &Plan) {
        (self.graph.graph_mut(), self.plans.get(&self.current))
    }
}
