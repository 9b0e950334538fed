//! Name resolution: every name in a graph file denotes one version with exactly one
//! writer. Checks that, and finds which pass each pass waits for.

use std::collections::hash_map::Entry;
use std::collections::{HashMap, HashSet};

use super::error::{ErrorKind, FileError};
use super::schema::{GraphFile, ResourceDecl};
use super::source::Source;
use crate::error::GraphError;

/// `reader` reads the version `writer` writes under `name`.
pub(super) struct Edge<'f> {
    pub writer: usize,
    pub reader: usize,
    pub name: &'f str,
}

/// Checks names and returns the dependencies between passes (indices in file order).
pub(super) fn resolve<'f>(
    source: &Source<'_>,
    file: &'f GraphFile<'_>,
    errors: &mut Vec<FileError>,
) -> Vec<Edge<'f>> {
    let declared = declared(source, file, errors);
    unique_passes_and_slots(source, file, errors);
    let imported = |name: &str| declared.get(name).is_some_and(|d| d.imported());
    let pass_name = |p: usize| file.passes[p].name.as_str().to_owned();

    let mut writers: HashMap<&str, usize> = HashMap::new();
    // Version name -> the pass modifying it and the name of the version it makes.
    let mut modifiers: HashMap<&str, (usize, &str)> = HashMap::new();
    for (p, pass) in file.passes.iter().enumerate() {
        for (slot, out) in &pass.outputs.0 {
            let name = out.as_str();
            match pass.input(slot.as_str()) {
                // Reading what it writes: reported with the reads below.
                Some(input) if input.as_str() == name => {}
                Some(input) => {
                    if declared.contains_key(name) {
                        let kind = ErrorKind::VersionNameTaken {
                            pass: pass_name(p),
                            resource: name.to_owned(),
                        };
                        errors.push(source.error(out, kind));
                    }
                    match modifiers.entry(input.as_str()) {
                        Entry::Occupied(first) => {
                            let kind = ErrorKind::ModifiedTwice {
                                first: pass_name(first.get().0),
                                second: pass_name(p),
                                resource: input.as_str().to_owned(),
                            };
                            errors.push(source.error(input, kind));
                        }
                        Entry::Vacant(v) => {
                            v.insert((p, name));
                        }
                    }
                }
                None if !declared.contains_key(name) => {
                    let kind = ErrorKind::Undeclared {
                        pass: pass_name(p),
                        resource: name.to_owned(),
                    };
                    errors.push(source.error(out, kind));
                }
                None => {}
            }
            match writers.entry(name) {
                Entry::Occupied(first) => {
                    let kind = ErrorKind::TwoWriters {
                        first: pass_name(*first.get()),
                        second: pass_name(p),
                        resource: name.to_owned(),
                    };
                    errors.push(source.error(out, kind));
                }
                Entry::Vacant(v) => {
                    v.insert(p);
                }
            }
        }
    }

    let mut edges = Vec::new();
    for (p, pass) in file.passes.iter().enumerate() {
        for (_, input) in &pass.inputs.0 {
            let name = input.as_str();
            let kind = match writers.get(name) {
                Some(&w) if w == p => ErrorKind::SelfModify {
                    pass: pass_name(p),
                    resource: name.to_owned(),
                },
                Some(&writer) => {
                    edges.push(Edge {
                        writer,
                        reader: p,
                        name,
                    });
                    continue;
                }
                None if imported(name) => continue,
                None => ErrorKind::Graph(GraphError::ReadBeforeWrite {
                    pass: pass_name(p),
                    resource: name.to_owned(),
                }),
            };
            errors.push(source.error(input, kind));
        }
    }

    for out in &file.outputs {
        let name = out.as_str();
        if !writers.contains_key(name) && !imported(name) {
            let kind = ErrorKind::UnwrittenOutput {
                resource: name.to_owned(),
            };
            errors.push(source.error(out, kind));
        }
        if let Some(&(p, next)) = modifiers.get(name) {
            let kind = ErrorKind::OutputNotFinal {
                resource: name.to_owned(),
                pass: pass_name(p),
                next: next.to_owned(),
            };
            errors.push(source.error(out, kind));
        }
    }
    edges
}

fn declared<'f>(
    source: &Source<'_>,
    file: &'f GraphFile<'_>,
    errors: &mut Vec<FileError>,
) -> HashMap<&'f str, &'f ResourceDecl> {
    let mut declared = HashMap::new();
    for (name, decl) in &file.resources.0 {
        if declared.insert(name.as_str(), decl).is_some() {
            let kind = ErrorKind::DuplicateResource {
                resource: name.as_str().to_owned(),
            };
            errors.push(source.error(name, kind));
        }
    }
    declared
}

fn unique_passes_and_slots(source: &Source<'_>, file: &GraphFile<'_>, errors: &mut Vec<FileError>) {
    let mut passes = HashSet::new();
    for pass in &file.passes {
        if !passes.insert(pass.name.as_str()) {
            let kind = ErrorKind::DuplicatePass {
                pass: pass.name.as_str().to_owned(),
            };
            errors.push(source.error(&pass.name, kind));
        }
        for (side, slots) in [("inputs", &pass.inputs), ("outputs", &pass.outputs)] {
            let mut seen = HashSet::new();
            for (slot, _) in &slots.0 {
                if !seen.insert(slot.as_str()) {
                    let kind = ErrorKind::DuplicateSlot {
                        pass: pass.name.as_str().to_owned(),
                        slot: slot.as_str().to_owned(),
                        side,
                    };
                    errors.push(source.error(slot, kind));
                }
            }
        }
    }
}
