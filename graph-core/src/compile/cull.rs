//! Culling: keep what contributes to an output, an import or a side effect; record why
//! everything else was dropped.

use crate::graph::Graph;
use crate::handle::{PassId, ResourceId};

use super::versions::Versions;

pub(super) struct Live {
    pub passes: Vec<bool>,
    /// Why each culled pass was culled (`None` for live passes).
    pub pass_reasons: Vec<Option<String>>,
    /// Why each unallocated resource is not needed (`None` for live resources).
    pub resource_reasons: Vec<Option<String>>,
}

impl Live {
    pub fn pass(&self, id: PassId) -> bool {
        self.passes[id.index()]
    }
}

pub(super) fn cull(graph: &Graph, versions: &Versions) -> Live {
    let passes = mark_live_passes(graph, versions);
    let pass_reasons = graph
        .passes
        .iter()
        .enumerate()
        .map(|(i, _)| (!passes[i]).then(|| why_culled(graph, versions, PassId(i as u32))))
        .collect();
    let resource_reasons = (0..graph.resources.len())
        .map(|r| why_unused(graph, versions, &passes, ResourceId(r as u32)))
        .collect();
    Live {
        passes,
        pass_reasons,
        resource_reasons,
    }
}

/// Walks back from the roots along read edges, a history's to its source's writer.
fn mark_live_passes(graph: &Graph, versions: &Versions) -> Vec<bool> {
    let mut live = vec![false; graph.passes.len()];
    let mut work: Vec<PassId> = graph
        .passes
        .iter()
        .enumerate()
        .filter(|(_, p)| p.side_effect)
        .map(|(i, _)| PassId(i as u32))
        .collect();
    for (r, resource) in graph.resources.iter().enumerate() {
        let id = ResourceId(r as u32);
        if resource.is_root() {
            let last = (id, versions.final_version(id));
            work.extend(versions.writer(last));
        }
    }
    while let Some(pass) = work.pop() {
        if std::mem::replace(&mut live[pass.index()], true) {
            continue;
        }
        for access in &graph.passes[pass.index()].accesses {
            if let Some(v) = access.read_version() {
                work.extend(versions.writer((access.resource, v)));
                // A history read is of what the source's writer leaves this frame for
                // the next: that pass lives while the history has a reader, whether or
                // not the source is still an output (a view showing one output).
                if let Some(of) = graph.resources[access.resource.index()].origin.history_of() {
                    work.extend(versions.writer((of, versions.final_version(of))));
                }
            }
        }
    }
    live
}

fn why_culled(graph: &Graph, versions: &Versions, pass: PassId) -> String {
    let name = |p: &PassId| format!("\"{}\"", graph.passes[p.index()].name);
    let reasons: Vec<String> = graph.passes[pass.index()]
        .accesses
        .iter()
        .filter_map(|a| a.written.map(|w| (a.resource, w)))
        .map(|(r, w)| {
            let resource = &graph.resources[r.index()].name;
            let readers = versions.readers((r, w));
            if !readers.is_empty() {
                let names: Vec<String> = readers.iter().map(name).collect();
                format!(
                    "\"{resource}\" is read only by culled passes ({})",
                    names.join(", ")
                )
            } else if let Some(next) = versions.overwriter((r, w)) {
                format!(
                    "\"{resource}\" is overwritten by {} before anything reads it",
                    name(&next)
                )
            } else {
                format!("nothing reads \"{resource}\" and it is not an output")
            }
        })
        .collect();
    if reasons.is_empty() {
        "it writes nothing and is not marked as a side effect".into()
    } else {
        reasons.join("; ")
    }
}

fn why_unused(
    graph: &Graph,
    versions: &Versions,
    live: &[bool],
    resource: ResourceId,
) -> Option<String> {
    let users = &versions.users[resource.index()];
    if users.iter().any(|p| live[p.index()]) {
        None
    } else if users.is_empty() {
        Some("no pass uses it".into())
    } else {
        let names: Vec<String> = users
            .iter()
            .map(|p| format!("\"{}\"", graph.passes[p.index()].name))
            .collect();
        Some(format!("used only by culled passes ({})", names.join(", ")))
    }
}
