//! Declaring a checked, ordered graph file through the same [`GraphBuilder`] code uses:
//! resources in file order, then each pass's plugin with the handles of its slots.

use std::collections::{BTreeMap, HashMap};

use super::any_handle::AnyHandle;
use super::conditions::FileConditions;
use super::error::{ErrorKind, FileError, FileErrors};
use super::loaded::{LoadedGraph, Names};
use super::params::GraphParams;
use super::plugin::Prepared;
use super::plugin_error::PluginError;
use super::references::References;
use super::schema::{GraphFile, PassDecl, Used};
use super::slots::Slots;
use super::source::Source;
use super::spans::Spans;
use crate::builder::GraphBuilder;
use crate::pass::PassKind;

/// Where a pass from parts came from: `parts/a.ron (used at graph.ron:3:5), in parts/b.ron
/// (used at parts/a.ron:9:9)`, the innermost part first.
fn shown_uses(used: &[Used]) -> String {
    used.iter()
        .rev()
        .map(|u| format!("{} (used at {})", u.part, u.at))
        .collect::<Vec<_>>()
        .join(", in ")
}

/// Declares `file` with passes in `order`. `prepared` holds each pass's plugin with its
/// parameters, by file index; conditions were read and names resolved without errors.
pub(super) fn declare<'f>(
    source: &Source<'f>,
    file: &'f GraphFile<'_>,
    mut prepared: Vec<Option<Box<dyn Prepared + '_>>>,
    mut conditions: FileConditions,
    order: &[usize],
    params: GraphParams,
    references: &'f References,
) -> Result<LoadedGraph, FileErrors> {
    let mut graph = GraphBuilder::new();
    graph.declare_features(conditions.features.iter());
    let mut handles: HashMap<&'f str, AnyHandle> = HashMap::new();
    let mut errors = Vec::new();
    let resources = file.resources.0.iter().zip(&mut conditions.resources);
    let mut resources: Vec<_> = resources.zip(&mut conditions.formats).collect();
    // Histories last, so each finds its source wherever the file declares it.
    resources.sort_by_key(|(((_, decl), _), _)| decl.history_of().is_some());
    for (((name, decl), condition), formats) in resources {
        let taken = std::mem::take(formats);
        let handle = match decl.declare(&mut graph, name.as_str(), taken, &params, &handles) {
            Ok(handle) => handle,
            Err(error) => {
                let at = decl.history_of().unwrap_or(name);
                errors.push(source.error(at, ErrorKind::Graph(error)));
                continue;
            }
        };
        if let Some(condition) = condition.take() {
            match handle {
                AnyHandle::Texture(h) => graph.when(h, condition),
                AnyHandle::Buffer(h) => graph.when(h, condition),
            }
        }
        handles.insert(name.as_str(), handle);
    }
    let declared = handles.clone();
    let mut spans = Spans::new(source, file);
    let mut plugins = BTreeMap::new();
    let mut slots_taken = BTreeMap::new();
    for &p in order {
        let decl = &file.passes[p];
        // A pass whose inputs a failed pass should have written is skipped: the failure
        // is reported already, and its consequences would only repeat it.
        let plugin = prepared.get_mut(p).and_then(Option::take);
        let dir = source.dir_of(&decl.name);
        let slots = Slots::new(decl, &handles, &declared, (dir, references));
        let (Some(plugin), Some(mut slots)) = (plugin, slots) else {
            continue;
        };
        record_uses(source, decl, &handles, &graph, &mut spans);
        let name = decl.name.as_str();
        let mut pass = match plugin.kind() {
            PassKind::Render => graph.add_render_pass(name),
            PassKind::Compute => graph.add_compute_pass(name),
            PassKind::Transfer => graph.add_transfer_pass(name),
        };
        if let Some(condition) = conditions.passes[p].take() {
            pass.when(condition);
        }
        if !decl.used.is_empty() {
            pass.origin(shown_uses(&decl.used));
        }
        errors.extend(optional_slots(source, decl));
        if let Err(error) = plugin.setup(&mut pass, &mut slots) {
            errors.push(plugin_error(source, decl, error));
            continue;
        }
        plugins.insert(name.to_owned(), decl.plugin.as_str().to_owned());
        let finished = slots.finish();
        let taken = finished.taken.iter().map(|&(slot, h)| (slot.to_owned(), h));
        slots_taken.insert(name.to_owned(), taken.collect());
        for handle in &finished.optional {
            match *handle {
                AnyHandle::Texture(h) => pass.optional(h),
                AnyHandle::Buffer(h) => pass.optional(h),
            };
        }
        for (slot, resource) in finished.unused {
            let kind = ErrorKind::UnusedSlot {
                pass: name.to_owned(),
                plugin: decl.plugin.as_str().to_owned(),
                slot: slot.to_owned(),
                resource: resource.to_owned(),
            };
            let at = decl.input(slot).or_else(|| decl.output(slot));
            errors.extend(at.map(|n| source.error(n, kind)));
        }
        // Of alternatives writing one name, readers get the last one declared; where it
        // is dropped, compiling stands the live one in for it.
        handles.extend(finished.written.into_iter().map(|(_, out, h)| (out, h)));
    }
    for out in &file.outputs {
        match handles.get(out.as_str()) {
            Some(AnyHandle::Texture(h)) => graph.export(*h),
            Some(AnyHandle::Buffer(h)) => graph.export(*h),
            None => {}
        }
    }
    if !errors.is_empty() {
        return Err(FileErrors::sorted(errors));
    }
    Ok(LoadedGraph {
        graph: graph.build(),
        names: Names(
            handles
                .into_iter()
                .map(|(n, h)| (n.to_owned(), h))
                .collect(),
        ),
        plugins,
        slots: slots_taken,
        params,
        spans,
    })
}

/// A pass's `optional` may name only its input-only slots and its output-only slots (a
/// fresh write, dropped with its resource): a modification must find what it reads.
fn optional_slots<'s>(
    source: &'s Source<'_>,
    decl: &'s PassDecl<'_>,
) -> impl Iterator<Item = FileError> + 's {
    decl.optional.iter().filter_map(move |slot| {
        let why = match (decl.input(slot.as_str()), decl.output(slot.as_str())) {
            (Some(_), None) | (None, Some(_)) => return None,
            (Some(_), Some(_)) => "is in its inputs and outputs: a modification cannot be optional",
            (None, None) => "is not one of its inputs or outputs",
        };
        let kind = ErrorKind::OptionalSlot {
            pass: decl.name.as_str().to_owned(),
            slot: slot.as_str().to_owned(),
            why: why.to_owned(),
        };
        Some(source.error(slot, kind))
    })
}

/// Remembers where the pass names each resource, for placing compile errors.
fn record_uses(
    source: &Source<'_>,
    decl: &PassDecl<'_>,
    handles: &HashMap<&str, AnyHandle>,
    graph: &GraphBuilder,
    spans: &mut Spans,
) {
    for (slot, name) in decl.inputs.0.iter().chain(&decl.outputs.0) {
        let read = decl.input(slot.as_str()).unwrap_or(name);
        if let Some(h) = handles.get(read.as_str()) {
            let resource = &graph.resources[h.id().index()].name;
            spans.record_use(decl.name.as_str(), resource, source.locate(name));
        }
    }
}

/// Places a plugin error at the slot it is about, else at the file reference it is about
/// (where the parameters write it as a plain string), else at the parameters, else at the
/// pass's name.
fn plugin_error(source: &Source<'_>, decl: &PassDecl<'_>, error: PluginError) -> FileError {
    let slot = error
        .slot()
        .and_then(|slot| decl.input(slot).or_else(|| decl.output(slot)));
    let location = match (slot, &decl.params) {
        (Some(name), _) => source.locate(name),
        (None, Some(params)) => {
            let params = params.0.get_ron();
            let quoted = error.reference().map(|r| format!("\"{r}\""));
            match quoted.and_then(|q| params.find(&q)) {
                Some(at) => source.locate_raw_at(params, at),
                None => source.locate_raw(params),
            }
        }
        (None, None) => source.locate(&decl.name),
    };
    FileError {
        location,
        kind: ErrorKind::Plugin {
            pass: decl.name.as_str().to_owned(),
            plugin: decl.plugin.as_str().to_owned(),
            error,
        },
    }
}
