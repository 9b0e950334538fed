//! What every compiled plan promises about the graph it was compiled from.

use std::collections::HashMap;

use rgraph_core::types::TextureUsages;
use rgraph_core::{Graph, Origin, PassId, Plan, ResourceId, Store};

/// What the declared accesses say about each version: who produced it and the last one.
struct Versions {
    writer: HashMap<(ResourceId, u32), PassId>,
    last: Vec<u32>,
}

impl Versions {
    fn of(graph: &Graph) -> Self {
        let mut writer = HashMap::new();
        let mut last = vec![0; graph.resources().len()];
        for (i, pass) in graph.passes().iter().enumerate() {
            for a in &pass.accesses {
                if let Some(w) = a.written {
                    writer.insert((a.resource, w), PassId(i as u32));
                    last[a.resource.index()] = last[a.resource.index()].max(w);
                }
            }
        }
        Self { writer, last }
    }
}

/// Checks everything a plan promises about the graph it was compiled from.
pub fn check_plan(graph: &Graph, plan: &Plan) {
    let versions = Versions::of(graph);
    let position: HashMap<PassId, usize> = plan
        .passes
        .iter()
        .enumerate()
        .map(|(i, p)| (p.id, i))
        .collect();
    assert_eq!(position.len(), plan.passes.len(), "a pass runs twice");
    assert_eq!(
        plan.passes.len() + plan.culled.len(),
        graph.passes().len(),
        "every pass either runs or is culled"
    );
    check_roots_and_inputs(graph, &versions, &position);
    check_version_order(graph, &position);
    check_lifetimes(graph, plan, &position);
    check_sharing(plan);
    check_usages_and_stores(graph, plan, &versions, &position);
}

/// Roots run, and whatever a running pass reads was produced by a running pass.
fn check_roots_and_inputs(graph: &Graph, versions: &Versions, position: &HashMap<PassId, usize>) {
    for (i, pass) in graph.passes().iter().enumerate() {
        let id = PassId(i as u32);
        if pass.side_effect {
            assert!(
                position.contains_key(&id),
                "side-effect {} culled",
                pass.name
            );
        }
        if !position.contains_key(&id) {
            continue;
        }
        for a in &pass.accesses {
            if let Some(v) = a.read_version() {
                if let Some(writer) = versions.writer.get(&(a.resource, v)) {
                    assert!(
                        matches!(position.get(writer), Some(w) if *w < position[&id]),
                        "{} runs without its input, or before it",
                        pass.name
                    );
                }
            }
        }
    }
    for (r, resource) in graph.resources().iter().enumerate() {
        let last = (ResourceId(r as u32), versions.last[r]);
        if let (true, Some(writer)) = (resource.is_root(), versions.writer.get(&last)) {
            assert!(
                position.contains_key(writer),
                "the final writer of {} culled",
                resource.name
            );
        }
    }
}

/// On each resource, running accesses happen in version order: a read of version `v` comes
/// after every running write up to `v` and before every running write past it.
fn check_version_order(graph: &Graph, position: &HashMap<PassId, usize>) {
    // Per resource: (position, version read, version written) of each running access.
    type Event = (usize, Option<u32>, Option<u32>);
    let mut events: HashMap<ResourceId, Vec<Event>> = HashMap::new();
    for (i, pass) in graph.passes().iter().enumerate() {
        let Some(&at) = position.get(&PassId(i as u32)) else {
            continue;
        };
        for a in &pass.accesses {
            events
                .entry(a.resource)
                .or_default()
                .push((at, a.read_version(), a.written));
        }
    }
    for (resource, events) in events {
        for &(read_at, read, _) in &events {
            for &(write_at, _, written) in &events {
                let (Some(v), Some(w)) = (read, written) else {
                    continue;
                };
                if read_at != write_at {
                    assert_eq!(
                        read_at < write_at,
                        w > v,
                        "{resource:?}: read of v{v} at {read_at}, write of v{w} at {write_at}"
                    );
                }
            }
        }
        let mut writes: Vec<(u32, usize)> = events
            .iter()
            .filter_map(|e| e.2.map(|w| (w, e.0)))
            .collect();
        writes.sort();
        assert!(
            writes.windows(2).all(|w| w[0].1 <= w[1].1),
            "{resource:?}: writes out of version order {writes:?}"
        );
    }
}

fn check_lifetimes(graph: &Graph, plan: &Plan, position: &HashMap<PassId, usize>) {
    let mut spans: Vec<Option<(usize, usize)>> = vec![None; graph.resources().len()];
    for (i, pass) in graph.passes().iter().enumerate() {
        let Some(&at) = position.get(&PassId(i as u32)) else {
            continue;
        };
        for a in &pass.accesses {
            let span = &mut spans[a.resource.index()];
            *span = Some(span.map_or((at, at), |(first, last)| (first.min(at), last.max(at))));
        }
    }
    for (r, resource) in graph.resources().iter().enumerate() {
        let expected = spans[r].map(|(first, last)| {
            (
                first,
                if resource.exported {
                    plan.passes.len() - 1
                } else {
                    last
                },
            )
        });
        assert_eq!(
            plan.resources[r].lifetime, expected,
            "lifetime of {}",
            resource.name
        );
    }
}

fn overlap(a: Option<(usize, usize)>, b: Option<(usize, usize)>) -> bool {
    let (Some(a), Some(b)) = (a, b) else {
        panic!("a pooled resource without a lifetime");
    };
    a.0 <= b.1 && b.0 <= a.1
}

/// Resources that share memory are alive at different times and are the same object.
fn check_sharing(plan: &Plan) {
    let mut allocated = 0;
    for (t, texture) in plan.textures.iter().enumerate() {
        for (i, &a) in texture.holds.iter().enumerate() {
            let ra = plan.resource(a);
            assert_eq!(ra.physical, Some(t));
            assert_eq!(ra.texture, Some(texture.shape), "{} shape", ra.name);
            assert_eq!(ra.texture_usage, texture.usage, "{} usage", ra.name);
            for &b in &texture.holds[i + 1..] {
                assert!(
                    !overlap(ra.lifetime, plan.resource(b).lifetime),
                    "{a:?} and {b:?} overlap"
                );
            }
        }
        allocated += texture.holds.len();
    }
    for (n, buffer) in plan.buffers.iter().enumerate() {
        for (i, &a) in buffer.holds.iter().enumerate() {
            let ra = plan.resource(a);
            assert_eq!(ra.physical, Some(n));
            assert_eq!(
                (ra.buffer_size, ra.buffer_usage),
                (Some(buffer.size), buffer.usage),
                "{} size and usage",
                ra.name
            );
            for &b in &buffer.holds[i + 1..] {
                assert!(
                    !overlap(ra.lifetime, plan.resource(b).lifetime),
                    "{a:?} and {b:?} overlap"
                );
            }
        }
        allocated += buffer.holds.len();
    }
    let pooled = plan
        .resources
        .iter()
        .filter(|r| r.origin == Origin::Transient && r.lifetime.is_some())
        .count();
    assert_eq!(allocated, pooled, "every live transient is allocated once");
    assert!(plan.memory.physical_bytes <= plan.memory.logical_bytes);
}

/// Every running access has its usage, transient attachments have nothing else, and no
/// attachment discards contents a later running pass reads.
fn check_usages_and_stores(
    graph: &Graph,
    plan: &Plan,
    versions: &Versions,
    position: &HashMap<PassId, usize>,
) {
    let mut read_later: HashMap<(ResourceId, u32), usize> = HashMap::new();
    for (&id, &at) in position {
        for a in &graph.passes()[id.index()].accesses {
            let resource = &plan.resources[a.resource.index()];
            assert!(resource.texture_usage.contains(a.role.texture_usage()));
            assert!(resource.buffer_usage.contains(a.role.buffer_usage()));
            if let Some(v) = a.read_version() {
                let latest = read_later.entry((a.resource, v)).or_insert(at);
                *latest = (*latest).max(at);
            }
        }
    }
    for r in &plan.resources {
        if r.texture_usage
            .contains(TextureUsages::TRANSIENT_ATTACHMENT)
        {
            assert_eq!(
                r.texture_usage,
                TextureUsages::RENDER_ATTACHMENT | TextureUsages::TRANSIENT_ATTACHMENT
            );
        }
    }
    for (at, pass) in plan.passes.iter().enumerate() {
        let accesses = &graph.passes()[pass.id.index()].accesses;
        let discarded = pass
            .color
            .iter()
            .filter(|c| c.ops.store == Store::Discard)
            .map(|c| c.resource)
            .chain(pass.depth_stencil.iter().filter_map(|ds| {
                let stores = ds
                    .depth
                    .iter()
                    .map(|o| o.store)
                    .chain(ds.stencil.iter().map(|o| o.store));
                stores
                    .into_iter()
                    .any(|s| s == Store::Discard)
                    .then_some(ds.resource)
            }));
        for resource in discarded {
            for a in accesses.iter().filter(|a| a.resource == resource) {
                let Some(w) = a.written else { continue };
                let root = graph.resources()[resource.index()].is_root()
                    && w == versions.last[resource.index()];
                assert!(!root, "{}: discards the final version of a root", pass.name);
                if let Some(&reader) = read_later.get(&(resource, w)) {
                    assert!(
                        reader <= at,
                        "{}: discards what a later pass reads",
                        pass.name
                    );
                }
            }
        }
    }
}
