//! Ordering passes so that each is declared after the passes whose outputs it reads:
//! graph files list passes in any order, but the builder needs a version's handle before
//! a reader can use it.

use std::collections::BTreeSet;

use petgraph::algo::tarjan_scc;
use petgraph::graph::{DiGraph, NodeIndex};

use super::error::{ErrorKind, FileError};
use super::names::Edge;
use super::schema::GraphFile;
use super::source::Source;
use crate::error::GraphError;

/// Pass indices in dependency order; among passes free to go, file order decides, so a
/// file listed in a valid order keeps it. Each cycle is reported at its first pass (in
/// file order; for a preset, at the first of its changed inputs that closes it), and its
/// passes are left out of the order.
pub(super) fn sort(
    source: &Source<'_>,
    file: &GraphFile<'_>,
    edges: &[Edge<'_>],
    errors: &mut Vec<FileError>,
) -> Vec<usize> {
    let n = file.passes.len();
    let mut waiting_on = vec![0usize; n];
    let mut readers = vec![Vec::new(); n];
    for e in edges {
        waiting_on[e.reader] += 1;
        readers[e.writer].push(e.reader);
    }
    let mut ready: BTreeSet<usize> = (0..n).filter(|&p| waiting_on[p] == 0).collect();
    let mut order = Vec::with_capacity(n);
    while let Some(p) = ready.pop_first() {
        order.push(p);
        for &r in &readers[p] {
            waiting_on[r] -= 1;
            if waiting_on[r] == 0 {
                ready.insert(r);
            }
        }
    }
    if order.len() < n {
        report_cycles(source, file, edges, &waiting_on, errors);
    }
    order
}

/// Reports every strongly connected group of passes still waiting: each is a cycle.
/// Passes that wait only on a cycle are not cycles themselves and are not reported.
fn report_cycles(
    source: &Source<'_>,
    file: &GraphFile<'_>,
    edges: &[Edge<'_>],
    waiting_on: &[usize],
    errors: &mut Vec<FileError>,
) {
    let stuck = |p: usize| waiting_on[p] > 0;
    // Node i is pass i.
    let mut graph = DiGraph::<(), ()>::new();
    for _ in &file.passes {
        graph.add_node(());
    }
    for e in edges.iter().filter(|e| stuck(e.writer) && stuck(e.reader)) {
        graph.add_edge(NodeIndex::new(e.writer), NodeIndex::new(e.reader), ());
    }
    for component in tarjan_scc(&graph).into_iter().filter(|c| c.len() > 1) {
        let mut cycle: Vec<usize> = component.iter().map(|n| n.index()).collect();
        cycle.sort_unstable();
        let mut resources: Vec<String> = Vec::new();
        for e in edges {
            let inside = cycle.contains(&e.writer) && cycle.contains(&e.reader);
            if inside && !resources.iter().any(|r| r == e.name) {
                resources.push(e.name.to_owned());
            }
        }
        // A preset that closed the cycle by changing a pass's inputs is where to fix it.
        let changed = edges
            .iter()
            .filter(|e| cycle.contains(&e.writer) && cycle.contains(&e.reader))
            .filter_map(|e| {
                let inputs = &file.passes[e.reader].inputs.0;
                inputs
                    .iter()
                    .map(|(_, name)| name)
                    .find(|n| n.as_str() == e.name)
            })
            .find(|name| source.in_preset(name.as_str()));
        let at = changed.unwrap_or(&file.passes[cycle[0]].name);
        let kind = ErrorKind::Graph(GraphError::Cycle {
            passes: cycle
                .iter()
                .map(|&p| file.passes[p].name.as_str().to_owned())
                .collect(),
            resources,
        });
        errors.push(source.error(at, kind));
    }
}
