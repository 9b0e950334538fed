//! Applying conditions, the first phase: passes and resources whose condition is false
//! for the compiled features are dropped, as are passes their plugin omitted
//! ([`PassBuilder::omit`](crate::PassBuilder::omit)), and the later phases see the graph
//! these features make.
//!
//! Dropping keeps every id: a dropped pass stays as a node without accesses (the
//! culling phase never reaches it) and a dropped resource stays unexported and unused.
//! Live passes are rewired through what was dropped, version by version:
//! - a version written by a dropped pass that another pass writes too (under an
//!   exclusive condition) is that pass's version: the two are alternatives;
//! - a version a dropped pass made by modifying its input is that input: the
//!   modification passes through, and readers of `n + 1` read `n`;
//! - a version a dropped pass wrote fresh is lost: reading it is an error naming both
//!   passes, and writing over it writes over what the dropped pass would have.
//!
//! An optional read ([`PassBuilder::optional`](crate::PassBuilder::optional)) of a lost
//! version, or of a dropped resource, is dropped from its pass instead of failing, and
//! [`Conditioned::dropped_reads`] says why; so is an optional fresh write of a dropped
//! resource.
//!
//! Textures with conditional formats get the one the features pick (see
//! [`formats`](super::formats)).

use crate::access::{Access, DroppedRead};
use crate::condition::{Condition, Features};
use crate::error::GraphError;
use crate::graph::Graph;
use crate::handle::{PassId, ResourceId};

/// The graph for one feature set, and why things are missing from it.
pub(super) struct Conditioned {
    /// Same ids as the declared graph; see the module documentation.
    pub graph: Graph,
    /// Why each pass is dropped (`condition "x" is false`), `None` where it stays.
    pub passes: Vec<Option<String>>,
    /// Why each resource is dropped, `None` where it stays.
    pub resources: Vec<Option<String>>,
    /// Why each texture's format is a conditional one, `None` where it is as declared.
    pub formats: Vec<Option<String>>,
    /// Each pass's optional reads dropped from it, as declared, with why.
    pub dropped_reads: Vec<Vec<DroppedRead>>,
    pub errors: Vec<GraphError>,
}

impl Conditioned {
    pub fn pass_dropped(&self, pass: usize) -> bool {
        self.passes[pass].is_some()
    }

    pub fn resource_dropped(&self, resource: usize) -> bool {
        self.resources[resource].is_some()
    }
}

/// Drops what `features` excludes and rewires the rest; see the module documentation.
pub(super) fn apply(graph: &Graph, features: &Features) -> Conditioned {
    let mut errors = Vec::new();
    undeclared_features(graph, &mut errors);
    alternatives_exclusive(graph, &mut errors);
    let why = |c: &Option<Condition>| c.as_ref().and_then(|c| c.why_false(features));
    let passes: Vec<Option<String>> = graph
        .passes
        .iter()
        .map(|p| p.omitted.clone().or_else(|| why(&p.condition)))
        .collect();
    let resources: Vec<Option<String>> =
        graph.resources.iter().map(|r| why(&r.condition)).collect();
    let mut chosen = graph.resources.clone();
    let formats = chosen
        .iter_mut()
        .map(|r| super::formats::choose(r, features))
        .collect();
    let mut conditioned = Conditioned {
        graph: Graph {
            resources: chosen,
            passes: graph.passes.iter().map(|p| p.declaration()).collect(),
            features: graph.features.clone(),
            declare_errors: Vec::new(),
        },
        dropped_reads: vec![Vec::new(); graph.passes.len()],
        passes,
        resources,
        formats,
        errors,
    };
    // Misspelt features or clashing alternatives make what is dropped meaningless:
    // report them alone.
    if conditioned.errors.is_empty() {
        let aliases = Aliases::of(graph, &conditioned.passes);
        rewire(graph, &aliases, &mut conditioned);
        outputs_kept(graph, &aliases, &mut conditioned);
        live_writers_unique(&mut conditioned);
    }
    conditioned
}

/// Conditions may name only the features the graph declares: a misspelt feature would
/// otherwise drop a pass, or keep a format, for every scene.
fn undeclared_features(graph: &Graph, errors: &mut Vec<GraphError>) {
    let declared = graph.features.to_string();
    let unknown = |c: &Condition| -> Vec<String> {
        c.features()
            .filter(|f| !graph.features.contains(f))
            .map(str::to_owned)
            .collect()
    };
    for pass in &graph.passes {
        let Some(condition) = &pass.condition else {
            continue;
        };
        for feature in unknown(condition) {
            errors.push(GraphError::UnknownPassFeature {
                pass: pass.name.clone(),
                condition: condition.to_string(),
                feature,
                declared: declared.clone(),
            });
        }
    }
    for resource in &graph.resources {
        if let Some(condition) = &resource.condition {
            for feature in unknown(condition) {
                errors.push(GraphError::UnknownResourceFeature {
                    resource: resource.name.clone(),
                    condition: condition.to_string(),
                    feature,
                    declared: declared.clone(),
                });
            }
        }
        let format_conditions = resource.texture().map(|t| t.format_if.as_slice());
        for (condition, _) in format_conditions.unwrap_or_default() {
            for feature in unknown(condition) {
                errors.push(GraphError::UnknownFormatFeature {
                    resource: resource.name.clone(),
                    condition: condition.to_string(),
                    feature,
                    declared: declared.clone(),
                });
            }
        }
    }
}

/// Passes writing over the same version must have exclusive conditions, whatever the
/// features: then at most one of them is ever live. Checked on the declared graph so
/// that every feature set reports the same mistake.
fn alternatives_exclusive(graph: &Graph, errors: &mut Vec<GraphError>) {
    let versions = VersionTable::of(graph);
    for (r, rows) in versions.overwriters.iter().enumerate() {
        for (version, writers) in rows.iter().enumerate() {
            for (i, &(second, _)) in writers.iter().enumerate() {
                for &(first, _) in &writers[..i] {
                    let condition = |p: PassId| graph.passes[p.index()].condition.as_ref();
                    let exclusive = condition(first)
                        .zip(condition(second))
                        .is_some_and(|(a, b)| a.excludes(b));
                    if !exclusive {
                        push_new(
                            errors,
                            conflict(graph, first, second, ResourceId(r as u32), version),
                        );
                    }
                }
            }
        }
    }
}

/// After rewiring, two live passes may still write over one version (each wrote over a
/// different version of alternatives, say): a version has one writer.
fn live_writers_unique(conditioned: &mut Conditioned) {
    let versions = VersionTable::of(&conditioned.graph);
    for (r, rows) in versions.overwriters.iter().enumerate() {
        for (version, writers) in rows.iter().enumerate() {
            if let [(first, _), (second, _), ..] = writers[..] {
                let error = conflict(
                    &conditioned.graph,
                    first,
                    second,
                    ResourceId(r as u32),
                    version,
                );
                push_new(&mut conditioned.errors, error);
            }
        }
    }
}

fn conflict(
    graph: &Graph,
    first: PassId,
    second: PassId,
    resource: ResourceId,
    version: usize,
) -> GraphError {
    GraphError::ConflictingWriters {
        first: graph.passes[first.index()].name.clone(),
        second: graph.passes[second.index()].name.clone(),
        resource: graph.resources[resource.index()].name.clone(),
        version: version as u32,
    }
}

fn push_new(errors: &mut Vec<GraphError>, error: GraphError) {
    if !errors.contains(&error) {
        errors.push(error);
    }
}

/// Points every live access at the version it sees in this graph, drops the optional
/// reads of what is gone, and empties dropped passes.
fn rewire(graph: &Graph, aliases: &Aliases, conditioned: &mut Conditioned) {
    for (p, pass) in conditioned.graph.passes.iter_mut().enumerate() {
        if conditioned.passes[p].is_some() {
            pass.accesses.clear();
            pass.side_effect = false;
            continue;
        }
        let mut kept = Vec::with_capacity(pass.accesses.len());
        for mut access in std::mem::take(&mut pass.accesses) {
            let r = access.resource.index();
            let Some(alias) = aliases.get(access.resource, access.version) else {
                kept.push(access); // a foreign handle, which validation reports
                continue;
            };
            let name = &graph.resources[r].name;
            let gone = match (&conditioned.resources[r], alias.lost_by) {
                (Some(why), _) => Some(Gone::Resource(why)),
                (None, Some(lost_by)) if access.role.reads() => Some(Gone::Writer(lost_by)),
                (None, _) => None,
            };
            let writer_why =
                |pass: PassId| conditioned.passes[pass.index()].clone().unwrap_or_default();
            match gone {
                Some(gone) if access.optional => {
                    let why = match gone {
                        Gone::Resource(why) => format!("\"{name}\" is dropped: {why}"),
                        Gone::Writer(writer) => format!(
                            "its writer \"{}\" is dropped: {}",
                            graph.passes[writer.index()].name,
                            writer_why(writer)
                        ),
                    };
                    conditioned.dropped_reads[p].push(DroppedRead {
                        resource: access.resource,
                        version: access.version,
                        why,
                        writes: access.role.writes(),
                    });
                    continue;
                }
                Some(Gone::Resource(why)) => {
                    conditioned.errors.push(GraphError::UsesDroppedResource {
                        pass: pass.name.clone(),
                        resource: name.clone(),
                        why: why.clone(),
                    });
                    kept.push(access);
                    continue;
                }
                Some(Gone::Writer(lost_by)) => {
                    conditioned.errors.push(GraphError::DroppedWriter {
                        reader: pass.name.clone(),
                        dropped: graph.passes[lost_by.index()].name.clone(),
                        resource: name.clone(),
                        why: writer_why(lost_by),
                    });
                }
                None => {}
            }
            access.version = alias.version;
            kept.push(access);
        }
        pass.accesses = kept;
    }
    for (resource, why) in conditioned
        .graph
        .resources
        .iter_mut()
        .zip(&conditioned.resources)
    {
        resource.exported &= why.is_none();
    }
}

/// What an access finds gone in the conditioned graph.
enum Gone<'a> {
    /// The resource, for this reason.
    Resource(&'a String),
    /// The pass that alone wrote the version read.
    Writer(PassId),
}

/// An output whose final contents only a dropped pass wrote would be undefined.
fn outputs_kept(graph: &Graph, aliases: &Aliases, conditioned: &mut Conditioned) {
    for (r, resource) in conditioned.graph.resources.iter().enumerate() {
        let id = ResourceId(r as u32);
        let last = graph.resources[r].versions - 1;
        let lost_by = aliases.get(id, last).and_then(|a| a.lost_by);
        if let (true, Some(pass)) = (resource.exported, lost_by) {
            conditioned.errors.push(GraphError::DroppedOutput {
                resource: resource.name.clone(),
                dropped: graph.passes[pass.index()].name.clone(),
                why: conditioned.passes[pass.index()].clone().unwrap_or_default(),
            });
        }
    }
}

/// What a version is in the conditioned graph.
#[derive(Copy, Clone, Debug)]
struct Alias {
    /// The version whose contents it holds, or, when lost, whose memory it overwrites.
    version: u32,
    /// The dropped pass that alone wrote its contents.
    lost_by: Option<PassId>,
}

/// Aliases of every version, per resource.
struct Aliases(Vec<Vec<Alias>>);

impl Aliases {
    fn of(graph: &Graph, dropped: &[Option<String>]) -> Aliases {
        let table = VersionTable::of(graph);
        let live = |p: PassId| dropped[p.index()].is_none();
        let mut all = Vec::with_capacity(graph.resources.len());
        for (r, resource) in graph.resources.iter().enumerate() {
            let mut aliases: Vec<Alias> = Vec::with_capacity(resource.versions as usize);
            for v in 0..resource.versions {
                let own = Alias {
                    version: v,
                    lost_by: None,
                };
                let alias = match table.writers[r].get(v as usize).copied().flatten() {
                    Some((writer, _)) if live(writer) => own,
                    Some((writer, access)) => {
                        let incoming = access.version as usize;
                        let stand_in = table.overwriters[r][incoming]
                            .iter()
                            .find(|&&(p, _)| live(p));
                        // Versions count up, so the input's alias is already known.
                        let input = aliases[incoming];
                        match stand_in {
                            Some(&(_, made)) => Alias {
                                version: made,
                                lost_by: None,
                            },
                            None if access.role.reads() => input,
                            None => Alias {
                                version: input.version,
                                lost_by: Some(writer),
                            },
                        }
                    }
                    None => own,
                };
                aliases.push(alias);
            }
            all.push(aliases);
        }
        Aliases(all)
    }

    fn get(&self, resource: ResourceId, version: u32) -> Option<Alias> {
        self.0.get(resource.index())?.get(version as usize).copied()
    }
}

/// For each resource and version: the pass that wrote it (with the access), and the
/// passes that write over it (with the version each makes), in declaration order.
struct VersionTable {
    writers: Vec<Vec<Option<(PassId, Access)>>>,
    overwriters: Vec<Vec<Vec<(PassId, u32)>>>,
}

impl VersionTable {
    fn of(graph: &Graph) -> VersionTable {
        let rows = |r: &crate::resource::ResourceNode| r.versions as usize;
        let mut table = VersionTable {
            writers: graph
                .resources
                .iter()
                .map(|r| vec![None; rows(r)])
                .collect(),
            overwriters: graph
                .resources
                .iter()
                .map(|r| vec![Vec::new(); rows(r)])
                .collect(),
        };
        for (p, pass) in graph.passes.iter().enumerate() {
            let id = PassId(p as u32);
            for access in &pass.accesses {
                let (r, Some(made)) = (access.resource.index(), access.written) else {
                    continue;
                };
                if let Some(slot) = table
                    .writers
                    .get_mut(r)
                    .and_then(|w| w.get_mut(made as usize))
                {
                    *slot = Some((id, *access));
                }
                let over = table
                    .overwriters
                    .get_mut(r)
                    .and_then(|o| o.get_mut(access.version as usize));
                // One pass writing a resource twice is a usage conflict validation names.
                if let Some(over) = over.filter(|o| o.iter().all(|&(q, _)| q != id)) {
                    over.push((id, made));
                }
            }
        }
        table
    }
}
