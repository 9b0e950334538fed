//! Histories: a resource carried to the next frame. A history resource
//! ([`Origin::History`]) holds the previous frame's final contents of its source, a
//! graph-owned texture, so the compiler checks what makes that one well-defined value
//! (one pass writes the source, once; no pass writes the history) and plans the pair
//! apart from transient memory: the executor keeps both in textures of their own and
//! swaps them after each frame.
//!
//! Reads of the history need no order against the source's write: they read the other
//! texture of the pair, which nothing writes this frame, so the compiler adds no edge
//! between the history's readers and the source's writer.

use std::hash::{Hash, Hasher};

use crate::error::GraphError;
use crate::graph::Graph;
use crate::handle::{PassId, ResourceId};
use crate::plan::{HistoryEdge, Plan};
use crate::resource::{Origin, ResourceDesc, TextureShape};

use super::conditions::Conditioned;
use super::cull::Live;
use super::usage::Usages;
use super::versions::Versions;

/// For each resource, the history that carries it to the next frame, if any (the first,
/// where a graph declares two, which [`check`] reports).
pub(super) fn carried(graph: &Graph) -> Vec<Option<ResourceId>> {
    let mut carried = vec![None; graph.resources.len()];
    for (r, resource) in graph.resources.iter().enumerate() {
        if let Some(slot) = resource
            .origin
            .history_of()
            .and_then(|of| carried.get_mut(of.index()))
        {
            slot.get_or_insert(ResourceId(r as u32));
        }
    }
    carried
}

/// Checks every history the conditioned graph keeps: its source is a graph-owned texture
/// that it alone carries, which exactly one pass writes, once, and no pass writes the
/// history itself.
pub(super) fn check(conditioned: &Conditioned, errors: &mut Vec<GraphError>) {
    let graph = &conditioned.graph;
    let mut claimed: Vec<Option<&str>> = vec![None; graph.resources.len()];
    let kept = (0..graph.resources.len()).filter(|&r| !conditioned.resource_dropped(r));
    for r in kept {
        let history = &graph.resources[r];
        let Origin::History { of } = history.origin else {
            continue;
        };
        let Some(source) = graph.resources.get(of.index()) else {
            errors.push(GraphError::HistorySource {
                resource: history.name.clone(),
                of: format!("#{}", of.0),
                why: "it belongs to another graph".into(),
            });
            continue;
        };
        let fail = |why: String| GraphError::HistorySource {
            resource: history.name.clone(),
            of: source.name.clone(),
            why,
        };
        let why = match (&source.desc, source.origin) {
            (ResourceDesc::Buffer(_), _) => Some("it is a buffer; histories are textures".into()),
            (_, Origin::Imported) => Some(
                "it is imported; the engine owns it and keeps its previous contents itself".into(),
            ),
            (_, Origin::History { .. }) => Some("it is a history itself".into()),
            _ if conditioned.resource_dropped(of.index()) => Some(format!(
                "it is dropped where the history is not ({})",
                conditioned.resources[of.index()]
                    .clone()
                    .unwrap_or_default()
            )),
            (ResourceDesc::Texture(_), Origin::Transient) => {
                claimed[of.index()].map(|other| format!("\"{other}\" already carries it"))
            }
        };
        if let Some(why) = why {
            errors.push(fail(why));
            continue;
        }
        claimed[of.index()] = Some(&history.name);
        writes_once(conditioned, r, of, errors);
    }
}

/// Exactly one kept pass writes `of`, producing one version, and none writes the history
/// `r`.
fn writes_once(conditioned: &Conditioned, r: usize, of: ResourceId, errors: &mut Vec<GraphError>) {
    let graph = &conditioned.graph;
    let (history, source) = (&graph.resources[r], &graph.resources[of.index()]);
    let mut writers: Vec<&str> = Vec::new();
    for (p, pass) in graph.passes.iter().enumerate() {
        if conditioned.pass_dropped(p) {
            continue;
        }
        for access in pass.accesses.iter().filter(|a| a.written.is_some()) {
            if access.resource.index() == r {
                errors.push(GraphError::HistoryWritten {
                    pass: pass.name.clone(),
                    resource: history.name.clone(),
                    of: source.name.clone(),
                });
            } else if access.resource == of {
                writers.push(&pass.name);
            }
        }
    }
    match writers.as_slice() {
        [] => errors.push(GraphError::HistoryNeverWritten {
            resource: history.name.clone(),
            of: source.name.clone(),
        }),
        [_] => {}
        [first, second, ..] => errors.push(GraphError::HistoryWrittenTwice {
            of: source.name.clone(),
            history: history.name.clone(),
            first: (*first).to_owned(),
            second: (*second).to_owned(),
        }),
    }
}

/// The edge to the next frame of every history whose source a live pass writes and a
/// live pass reads, for a valid graph: who writes the version carried, who reads the
/// previous one (in execution order), and the pair's shape and usages (both textures
/// serve both roles). A history no live pass reads carries nothing: its source stays a
/// transient texture (the default pipeline's CPU branch, whose shadow atlas's history
/// only the GPU branch's passes read).
pub(super) fn edges(
    graph: &Graph,
    versions: &Versions,
    live: &Live,
    order: &[PassId],
    shapes: &[Option<TextureShape>],
    usages: &Usages,
) -> Vec<HistoryEdge> {
    let position = |p: &PassId| order.iter().position(|q| q == p);
    let name = |p: PassId| graph.passes[p.index()].name.clone();
    let mut edges = Vec::new();
    for (r, resource) in graph.resources.iter().enumerate() {
        let Some(of) = resource.origin.history_of() else {
            continue;
        };
        let version = versions.final_version(of);
        let (Some(writer), Some(shape)) = (versions.writer((of, version)), shapes[of.index()])
        else {
            continue;
        };
        // Culled with every reader of the history (cull.rs keeps it for any): nothing
        // carries, and the pair is not made.
        if !live.pass(writer) {
            continue;
        }
        let history = ResourceId(r as u32);
        let mut readers: Vec<PassId> = versions
            .readers((history, 0))
            .iter()
            .copied()
            .filter(|&p| live.pass(p))
            .collect();
        if readers.is_empty() {
            continue;
        }
        readers.sort_by_key(position);
        edges.push(HistoryEdge {
            source: of,
            history,
            version,
            writer: name(writer),
            readers: readers.into_iter().map(name).collect(),
            shape,
            usage: usages.texture[of.index()] | usages.texture[r],
            bytes: shape.bytes(),
        });
    }
    edges
}

/// A digest of the plan, for the executor to tell whether the plan it runs is the one
/// its histories were written under: 0 without histories, where nothing needs it.
/// Computed from the plan's JSON, so any difference the plan can show changes it.
pub(super) fn fingerprint(plan: &Plan) -> u64 {
    if plan.history.is_empty() {
        return 0;
    }
    let mut hasher = std::collections::hash_map::DefaultHasher::new();
    serde_json::to_string(plan)
        .unwrap_or_default()
        .hash(&mut hasher);
    hasher.finish().max(1)
}
