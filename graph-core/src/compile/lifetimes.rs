//! Lifetimes: the span of execution positions over which each resource must exist.

use crate::graph::Graph;
use crate::handle::PassId;

/// `(first, last)` position in the execution order for each resource; `None` when no
/// live pass uses it. Exported resources live to the end of the frame and beyond.
pub(super) fn lifetimes(graph: &Graph, order: &[PassId]) -> Vec<Option<(usize, usize)>> {
    let mut spans: Vec<Option<(usize, usize)>> = vec![None; graph.resources.len()];
    for (position, pass) in order.iter().enumerate() {
        for access in &graph.passes[pass.index()].accesses {
            let span = &mut spans[access.resource.index()];
            *span = Some(match *span {
                None => (position, position),
                Some((first, _)) => (first, position),
            });
        }
    }
    for (span, resource) in spans.iter_mut().zip(&graph.resources) {
        if let (Some((_, last)), true) = (span.as_mut(), resource.exported) {
            *last = order.len().saturating_sub(1).max(*last);
        }
    }
    spans
}
