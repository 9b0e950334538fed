//! Where a graph file uses its parameters, and the value each takes when it is loaded.

use super::error::{ErrorKind, FileError};
use super::params::GraphParams;
use super::schema::{Count, GraphFile, ParamUse};
use super::source::Source;
use crate::position::Position;

/// The parameters `file` declares with their defaults: what a tool checks before giving
/// a value (the bench sets `msaa` only in files that have it). Repeated uses of a name
/// give its first default; [`load_file_with`](super::load_file_with) reports conflicts.
pub(super) fn declared(file: &GraphFile<'_>) -> GraphParams {
    let mut declared = GraphParams::new();
    for (_, use_) in uses(file) {
        declared
            .0
            .entry(use_.name.as_str().to_owned())
            .or_insert(use_.default);
    }
    declared
}

/// Every parameter of `file` with the value it takes: `given`, else its default. Reports
/// a given name the file does not declare (at the file's start), a name used with two
/// defaults (at the second), and a value of 0 (at each use it would apply to).
pub(super) fn resolve(
    source: &Source<'_>,
    file: &GraphFile<'_>,
    given: &GraphParams,
    errors: &mut Vec<FileError>,
) -> GraphParams {
    let declared = declared(file);
    for (name, value) in given.iter() {
        if declared.get(name).is_none() {
            let names: Vec<&str> = declared.iter().map(|(n, _)| n).collect();
            errors.push(FileError {
                location: source.location(Position::START),
                kind: ErrorKind::UnknownParam {
                    name: name.to_owned(),
                    value,
                    declared: match names.is_empty() {
                        true => "none".into(),
                        false => names.join(", "),
                    },
                },
            });
        }
    }
    let values = GraphParams(
        declared
            .iter()
            .map(|(name, default)| (name.to_owned(), given.get(name).unwrap_or(default)))
            .collect(),
    );
    for ((resource, field), use_) in uses(file) {
        let name = use_.name.as_str();
        let first = declared.get(name).unwrap_or(use_.default);
        if use_.default != first {
            errors.push(source.error(
                &use_.name,
                ErrorKind::ParamDefaults {
                    name: name.to_owned(),
                    first,
                    second: use_.default,
                },
            ));
        }
        let value = values.get(name).unwrap_or(use_.default);
        if value == 0 {
            errors.push(source.error(
                &use_.name,
                ErrorKind::ParamValue {
                    name: name.to_owned(),
                    value,
                    resource: resource.to_owned(),
                    field,
                },
            ));
        }
    }
    values
}

/// Each parameter use in `file`, with the texture and field it sets, in file order.
fn uses<'f, 'a>(
    file: &'f GraphFile<'a>,
) -> impl Iterator<Item = ((&'f str, &'static str), &'f ParamUse<'a>)> {
    file.resources.0.iter().flat_map(|(name, decl)| {
        decl.texture()
            .into_iter()
            .flat_map(|t| t.counts())
            .filter_map(move |(field, count)| match count {
                Count::Param(p) => Some(((name.as_str(), field), p)),
                Count::Value(_) => None,
            })
    })
}
