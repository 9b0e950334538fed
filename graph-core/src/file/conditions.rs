//! The `features` a graph file declares, the `when` conditions of its passes and
//! resources and the conditions of its textures' `format_if`: parsed, and checked
//! against the declaration, each error at the character at fault.

use wgpu_types::TextureFormat;

use super::error::{ErrorKind, FileError};
use super::schema::{GraphFile, Name};
use super::source::Source;
use crate::condition::{Condition, Features};
use crate::error::GraphError;

/// The conditions of a graph file, by file index (`None` where there is none, or where
/// it is in error).
pub(super) struct FileConditions {
    pub features: Features,
    pub passes: Vec<Option<Condition>>,
    pub resources: Vec<Option<Condition>>,
    /// Each resource's conditional formats (those whose condition is not in error).
    pub formats: Vec<Vec<(Condition, TextureFormat)>>,
}

impl FileConditions {
    /// Whether passes `a` and `b` (file indices) can never both be in a graph.
    pub fn exclusive(&self, a: usize, b: usize) -> bool {
        match (&self.passes[a], &self.passes[b]) {
            (Some(a), Some(b)) => a.excludes(b),
            _ => false,
        }
    }

    /// The condition of pass `p` as written, for messages (`always` when it has none).
    pub fn shown(&self, p: usize) -> String {
        self.passes[p]
            .as_ref()
            .map_or_else(|| "always".into(), ToString::to_string)
    }
}

pub(super) fn read(
    source: &Source<'_>,
    file: &GraphFile<'_>,
    errors: &mut Vec<FileError>,
) -> FileConditions {
    let features = declared(source, file, errors);
    let passes = file
        .passes
        .iter()
        .map(|pass| {
            let owner = Owner::Pass(pass.name.as_str());
            let when = pass.when.as_ref()?;
            condition(source, &features, owner, when, errors)
        })
        .collect();
    let resources = file
        .resources
        .0
        .iter()
        .map(|(name, decl)| {
            let owner = Owner::Resource(name.as_str());
            condition(source, &features, owner, decl.when()?, errors)
        })
        .collect();
    let formats = file
        .resources
        .0
        .iter()
        .map(|(name, decl)| {
            let owner = Owner::Format(name.as_str());
            decl.format_if()
                .iter()
                .filter_map(|(when, format)| {
                    let condition = condition(source, &features, owner, when, errors)?;
                    Some((condition, *format))
                })
                .collect()
        })
        .collect();
    FileConditions {
        features,
        passes,
        resources,
        formats,
    }
}

/// The `features` list: each a feature name, each once.
fn declared(source: &Source<'_>, file: &GraphFile<'_>, errors: &mut Vec<FileError>) -> Features {
    let mut features = Features::new();
    for name in &file.features {
        let feature = name.as_str();
        let single = Condition::parse(feature)
            .ok()
            .filter(|c| c.literals().len() == 1 && !c.literals()[0].negated);
        let kind = match single {
            None => ErrorKind::BadFeature {
                feature: feature.to_owned(),
                why: "feature names are ASCII letters, digits and '_', not starting with a digit"
                    .into(),
            },
            Some(c) if !features.insert(c.literals()[0].feature.clone()) => {
                ErrorKind::DuplicateFeature {
                    feature: feature.to_owned(),
                }
            }
            Some(_) => continue,
        };
        errors.push(source.error(name, kind));
    }
    features
}

#[derive(Copy, Clone)]
enum Owner<'f> {
    Pass(&'f str),
    Resource(&'f str),
    /// A conditional format of the resource.
    Format(&'f str),
}

/// Parses one condition, and checks that it names declared features only.
fn condition(
    source: &Source<'_>,
    features: &Features,
    owner: Owner<'_>,
    when: &Name<'_>,
    errors: &mut Vec<FileError>,
) -> Option<Condition> {
    let text = when.as_str();
    let condition = match Condition::parse(text) {
        Ok(condition) => condition,
        Err(error) => {
            errors.push(FileError {
                location: source.locate_in(when, error.column()),
                kind: ErrorKind::BadCondition {
                    owner: match owner {
                        Owner::Pass(name) => format!("pass \"{name}\""),
                        Owner::Resource(name) => format!("resource \"{name}\""),
                        Owner::Format(name) => format!("resource \"{name}\" (format_if)"),
                    },
                    condition: text.to_owned(),
                    error,
                },
            });
            return None;
        }
    };
    let mut known = true;
    for feature in condition.features().filter(|f| !features.contains(f)) {
        known = false;
        let column = column_of(text, feature);
        let (condition, feature, declared) = (
            condition.to_string(),
            feature.to_owned(),
            features.to_string(),
        );
        let error = match owner {
            Owner::Pass(pass) => GraphError::UnknownPassFeature {
                pass: pass.to_owned(),
                condition,
                feature,
                declared,
            },
            Owner::Resource(resource) => GraphError::UnknownResourceFeature {
                resource: resource.to_owned(),
                condition,
                feature,
                declared,
            },
            Owner::Format(resource) => GraphError::UnknownFormatFeature {
                resource: resource.to_owned(),
                condition,
                feature,
                declared,
            },
        };
        errors.push(FileError {
            location: source.locate_in(when, column),
            kind: ErrorKind::Graph(error),
        });
    }
    known.then_some(condition)
}

/// The column (in characters) of `feature` as a whole name in `text`.
pub(super) fn column_of(text: &str, feature: &str) -> usize {
    let name_char = |c: char| c.is_ascii_alphanumeric() || c == '_';
    text.match_indices(feature)
        .find(|&(i, _)| {
            let before = text[..i].chars().next_back();
            let after = text[i + feature.len()..].chars().next();
            !before.is_some_and(name_char) && !after.is_some_and(name_char)
        })
        .map_or(0, |(i, _)| text[..i].chars().count())
}
