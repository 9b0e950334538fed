//! Ordering: a deterministic topological order of the live passes. Declaration order
//! breaks ties, so a graph declared in a sensible order runs in that order.

use std::cmp::Reverse;
use std::collections::BinaryHeap;

use petgraph::algo::tarjan_scc;
use petgraph::graph::{DiGraph, NodeIndex};
use petgraph::visit::EdgeRef;
use petgraph::Direction;

use crate::error::GraphError;
use crate::graph::Graph;
use crate::handle::{PassId, ResourceId};

use super::cull::Live;
use super::versions::{Version, Versions};

/// Live passes in execution order, or the cycle that prevents one.
pub(super) fn order(
    graph: &Graph,
    versions: &Versions,
    live: &Live,
) -> Result<Vec<PassId>, GraphError> {
    let deps = dependency_graph(graph, versions, live);
    let mut indegree: Vec<usize> = deps
        .node_indices()
        .map(|n| deps.neighbors_directed(n, Direction::Incoming).count())
        .collect();
    let mut ready: BinaryHeap<Reverse<PassId>> = deps
        .node_indices()
        .filter(|n| indegree[n.index()] == 0)
        .map(|n| Reverse(deps[n]))
        .collect();
    let mut order = Vec::with_capacity(deps.node_count());
    let mut nodes = vec![NodeIndex::end(); graph.passes.len()];
    for n in deps.node_indices() {
        nodes[deps[n].index()] = n;
    }
    while let Some(Reverse(pass)) = ready.pop() {
        order.push(pass);
        for next in deps.neighbors_directed(nodes[pass.index()], Direction::Outgoing) {
            indegree[next.index()] -= 1;
            if indegree[next.index()] == 0 {
                ready.push(Reverse(deps[next]));
            }
        }
    }
    if order.len() == deps.node_count() {
        Ok(order)
    } else {
        Err(cycle_error(graph, &deps))
    }
}

/// Edges between live passes: read-after-write, write-after-write and write-after-read,
/// each weighted with the resource that forces it. Parallel edges are harmless (the sort
/// counts and removes each one), so edges are added without looking for duplicates.
fn dependency_graph(
    graph: &Graph,
    versions: &Versions,
    live: &Live,
) -> DiGraph<PassId, ResourceId> {
    let mut deps = DiGraph::with_capacity(graph.passes.len(), graph.passes.len() * 2);
    let mut nodes = vec![NodeIndex::end(); graph.passes.len()];
    for (i, _) in graph.passes.iter().enumerate() {
        let id = PassId(i as u32);
        if live.pass(id) {
            nodes[i] = deps.add_node(id);
        }
    }
    let live_node = |p: PassId| live.pass(p).then(|| nodes[p.index()]);
    for (i, pass) in graph.passes.iter().enumerate() {
        let Some(this) = live_node(PassId(i as u32)) else {
            continue;
        };
        for access in &pass.accesses {
            let r = access.resource;
            if let Some(v) = access.read_version() {
                if let Some(producer) = versions.writer((r, v)).and_then(live_node) {
                    deps.add_edge(producer, this, r);
                }
            }
            if access.written.is_none() {
                continue;
            }
            // A write lands on the memory that last held a live version: it follows that
            // version's producer and every live pass that still reads it.
            let base = live_base(versions, live, (r, access.version));
            let producer = versions.writer(base).and_then(live_node);
            let readers = versions.readers(base).iter().copied().filter_map(live_node);
            for before in producer.into_iter().chain(readers) {
                if before != this {
                    deps.add_edge(before, this, r);
                }
            }
        }
    }
    deps
}

/// The latest version at or before `version` that a live pass produced, or version 0.
/// Versions between two live writes come from culled passes, and only culled passes read
/// them (a live read keeps its producer alive), so a live write orders itself against that
/// base. Each culled stretch is walked once, by the one live write that ends it.
fn live_base(versions: &Versions, live: &Live, (r, mut v): Version) -> Version {
    while v > 0 && !versions.writer((r, v)).is_some_and(|p| live.pass(p)) {
        v -= 1;
    }
    (r, v)
}

fn cycle_error(graph: &Graph, deps: &DiGraph<PassId, ResourceId>) -> GraphError {
    let component = tarjan_scc(deps)
        .into_iter()
        .find(|c| c.len() > 1)
        .unwrap_or_default();
    let mut resources: Vec<ResourceId> = deps
        .edge_references()
        .filter(|e| component.contains(&e.source()) && component.contains(&e.target()))
        .map(|e| *e.weight())
        .collect();
    resources.sort();
    resources.dedup();
    let mut passes: Vec<PassId> = component.iter().map(|&n| deps[n]).collect();
    passes.sort();
    GraphError::Cycle {
        passes: passes
            .iter()
            .map(|p| graph.passes[p.index()].name.clone())
            .collect(),
        resources: resources
            .iter()
            .map(|r| graph.resources[r.index()].name.clone())
            .collect(),
    }
}
