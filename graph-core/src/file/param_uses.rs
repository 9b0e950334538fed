//! Where a graph file uses its parameters, and the value each takes when it is loaded:
//! in textures (`samples`, `mips`, `layers`, an `Absolute` or `Divided` size), buffers
//! (`samples`, `texels`) and in passes' plugin
//! parameters, where `Param(name: "pad", default: 0)` stands for a whole number.

use std::ops::Range;

use super::error::{ErrorKind, FileError};
use super::params::GraphParams;
use super::schema::{options, Count, GraphFile, ParamUse};
use super::source::Source;
use crate::position::Position;

/// One use of a parameter.
struct Use<'f, 'a> {
    /// The texture or pass it is in.
    owner: &'f str,
    /// The texture's field, or "params" for a pass.
    field: &'static str,
    param: ParamUse<'a>,
}

/// The parameters `file` declares with their defaults: what a tool checks before giving
/// a value (the bench sets `msaa` only in files that have it). Repeated uses of a name
/// give its first default; [`load_file_with`](super::load_file_with) reports conflicts.
pub(super) fn declared(file: &GraphFile<'_>) -> GraphParams {
    let mut declared = GraphParams::new();
    for use_ in uses(file) {
        declared
            .0
            .entry(use_.param.name.as_str().to_owned())
            .or_insert(use_.param.default);
    }
    declared
}

/// Every parameter of `file` with the value it takes: `given`, else its default. Reports
/// a given name the file does not declare (at the file's start), a name used with two
/// defaults (at the second), and a value of 0 for a texture's count (at each use it would
/// apply to; a plugin judges the values of its own parameters).
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
    for Use {
        owner,
        field,
        param,
    } in uses(file)
    {
        let name = param.name.as_str();
        let first = declared.get(name).unwrap_or(param.default);
        if param.default != first {
            errors.push(source.error(
                &param.name,
                ErrorKind::ParamDefaults {
                    name: name.to_owned(),
                    first,
                    second: param.default,
                },
            ));
        }
        let value = values.get(name).unwrap_or(param.default);
        if value == 0 && field != PLUGIN_PARAMS {
            errors.push(source.error(
                &param.name,
                ErrorKind::ParamValue {
                    name: name.to_owned(),
                    value,
                    resource: owner.to_owned(),
                    field,
                },
            ));
        }
    }
    values
}

/// The field of a use in a pass's plugin parameters.
const PLUGIN_PARAMS: &str = "params";

/// Each parameter use in `file`: resources first, then passes, in file order.
fn uses<'f, 'a>(file: &'f GraphFile<'a>) -> Vec<Use<'f, 'a>> {
    let resources = file.resources.0.iter().flat_map(|(name, decl)| {
        decl.counts()
            .into_iter()
            .filter_map(move |(field, count)| match count {
                Count::Param(p) => Some(Use {
                    owner: name.as_str(),
                    field,
                    param: p.clone(),
                }),
                Count::Value(_) => None,
            })
    });
    let passes = file.passes.iter().flat_map(|pass| {
        let text = pass.params.as_ref().map_or("", |p| p.0.get_ron());
        in_plugin_params(text).into_iter().map(|(_, param)| Use {
            owner: pass.name.as_str(),
            field: PLUGIN_PARAMS,
            param,
        })
    });
    resources.chain(passes).collect()
}

/// The `Param(name: .., default: ..)` uses in a pass's plugin parameters, each with its
/// byte range in `text`. Text that only looks like one (in a string, or not parsing as
/// one) is left to the plugin, which reports it.
pub(super) fn in_plugin_params(text: &str) -> Vec<(Range<usize>, ParamUse<'_>)> {
    const START: &str = "Param(";
    let mut found = Vec::new();
    let mut from = 0;
    while let Some(at) = text[from..].find(START) {
        let start = from + at;
        from = start + START.len();
        // Part of a longer identifier (`MyParam(`) is not a use.
        let joined = text[..start]
            .chars()
            .next_back()
            .is_some_and(|c| c.is_alphanumeric() || c == '_');
        let Some(end) = text[start..].find(')').map(|e| start + e + 1) else {
            break;
        };
        if joined {
            continue;
        }
        if let Ok(param) = options().from_str::<ParamUse>(&text[start..end]) {
            found.push((start..end, param));
            from = end;
        }
    }
    found
}

/// `text` (a pass's plugin parameters) with each parameter use replaced by its value in
/// `values`, padded with spaces to the use's length (its line breaks kept), so the
/// plugin's errors keep their lines and columns.
pub(super) fn substitute(text: &str, values: &GraphParams) -> String {
    substitute_with(text, |param| {
        Some(values.get(param.name.as_str()).unwrap_or(param.default))
    })
}

/// `text` (a whole part file) with the uses of the parameters `values` names replaced by
/// their values, laid out as [`substitute`] does; other uses stay.
pub(super) fn substitute_given(text: &str, values: &GraphParams) -> String {
    substitute_with(text, |param| values.get(param.name.as_str()))
}

/// The names of the parameters `text` uses, sorted, each once.
pub(super) fn names(text: &str) -> Vec<String> {
    let mut names: Vec<String> = in_plugin_params(text)
        .into_iter()
        .map(|(_, param)| param.name.as_str().to_owned())
        .collect();
    names.sort();
    names.dedup();
    names
}

fn substitute_with(text: &str, value_of: impl Fn(&ParamUse<'_>) -> Option<u32>) -> String {
    let mut out = text.to_owned();
    for (range, param) in in_plugin_params(text).into_iter().rev() {
        let Some(value) = value_of(&param) else {
            continue;
        };
        let value = value.to_string();
        let padded: String = value
            .chars()
            .chain(text[range.clone()].chars().skip(value.len()).map(|c| {
                if c == '\n' {
                    c
                } else {
                    ' '
                }
            }))
            .collect();
        out.replace_range(range, &padded);
    }
    out
}
