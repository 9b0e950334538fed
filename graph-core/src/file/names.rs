//! Name resolution: every name in a graph file denotes one version with exactly one
//! writer. Checks that, and finds which pass each pass waits for.

use std::collections::{HashMap, HashSet};

use super::conditions::FileConditions;
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
/// Passes with exclusive conditions may write the same name: they are alternatives, and
/// its readers wait for all of them.
pub(super) fn resolve<'f>(
    source: &Source<'_>,
    file: &'f GraphFile<'_>,
    conditions: &FileConditions,
    errors: &mut Vec<FileError>,
) -> Vec<Edge<'f>> {
    let declared = declared(source, file, errors);
    unique_passes_and_slots(source, file, errors);
    let imported = |name: &str| declared.get(name).is_some_and(|d| d.imported());
    let pass_name = |p: usize| file.passes[p].name.as_str().to_owned();

    let mut writers: HashMap<&str, Vec<usize>> = HashMap::new();
    // Version name -> the passes modifying it and the name of the version each makes.
    let mut modifiers: HashMap<&str, Vec<(usize, &str)>> = HashMap::new();
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
                    let earlier = modifiers.entry(input.as_str()).or_default();
                    if let Some(&(first, _)) =
                        earlier.iter().find(|(q, _)| !conditions.exclusive(*q, p))
                    {
                        let kind = ErrorKind::ModifiedTwice {
                            first: pass_name(first),
                            second: pass_name(p),
                            resource: input.as_str().to_owned(),
                        };
                        errors.push(source.error(input, kind));
                    }
                    earlier.push((p, name));
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
            let earlier = writers.entry(name).or_default();
            if let Some(&first) = earlier.iter().find(|&&q| !conditions.exclusive(q, p)) {
                let kind = match (&conditions.passes[first], &conditions.passes[p]) {
                    (None, None) => ErrorKind::TwoWriters {
                        first: pass_name(first),
                        second: pass_name(p),
                        resource: name.to_owned(),
                    },
                    _ => ErrorKind::WritersNotExclusive {
                        first: pass_name(first),
                        second: pass_name(p),
                        resource: name.to_owned(),
                        first_when: conditions.shown(first),
                        second_when: conditions.shown(p),
                    },
                };
                errors.push(source.error(out, kind));
            }
            earlier.push(p);
        }
    }

    let mut edges = Vec::new();
    for (p, pass) in file.passes.iter().enumerate() {
        for (_, input) in &pass.inputs.0 {
            let name = input.as_str();
            let found = writers.get(name).map_or(&[][..], Vec::as_slice);
            let kind = match found {
                found if found.contains(&p) => ErrorKind::SelfModify {
                    pass: pass_name(p),
                    resource: name.to_owned(),
                },
                [_, ..] => {
                    edges.extend(found.iter().map(|&writer| Edge {
                        writer,
                        reader: p,
                        name,
                    }));
                    continue;
                }
                [] if imported(name) => continue,
                [] => ErrorKind::Graph(GraphError::ReadBeforeWrite {
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
        if let Some(&(p, next)) = modifiers.get(name).and_then(|m| m.first()) {
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
    file: &'f GraphFile<'f>,
    errors: &mut Vec<FileError>,
) -> HashMap<&'f str, &'f ResourceDecl<'f>> {
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
