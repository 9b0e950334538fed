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
use super::versions::Versions;

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
/// each weighted with the resource that forces it. Parallel edges are harmless here.
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
            let incoming = (access.resource, access.version);
            let producer = versions.writer.get(&incoming).copied().and_then(live_node);
            // Any use of a version, read or overwrite, follows its producer.
            if let Some(producer) = producer {
                deps.update_edge(producer, this, access.resource);
            }
            if access.written.is_some() {
                for reader in versions.readers(incoming) {
                    match live_node(*reader) {
                        Some(reader) if reader != this => {
                            deps.update_edge(reader, this, access.resource);
                        }
                        _ => {}
                    }
                }
            }
        }
    }
    deps
}

fn cycle_error(graph: &Graph, deps: &DiGraph<PassId, ResourceId>) -> GraphError {
    let component = tarjan_scc(deps)
        .into_iter()
        .find(|c| c.len() > 1)
        .unwrap_or_default();
    let resource = deps
        .edge_references()
        .find(|e| component.contains(&e.source()) && component.contains(&e.target()))
        .map(|e| graph.resources[e.weight().index()].name.clone())
        .unwrap_or_default();
    let mut passes: Vec<PassId> = component.iter().map(|&n| deps[n]).collect();
    passes.sort();
    GraphError::Cycle {
        passes: passes
            .iter()
            .map(|p| graph.passes[p.index()].name.clone())
            .collect(),
        resource,
    }
}
