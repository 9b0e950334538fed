//! Parameters of graph files: a texture's `samples`, `mips` or `layers` may be written
//! `Param(name: "msaa", default: 4)`, and the loader given a value for `"msaa"`, so one
//! file serves every sample count (`rgraph render --samples N`, the bench's sample sweep).
//!
//! Parameters apply when the file is loaded, not when it is compiled: plugins choose their
//! shaders in `setup` from the textures they are given (a 4x G-buffer reads
//! `texture_multisampled_2d`, a 1x one `texture_2d`), so a value is part of what the file
//! declares. A [`LoadedGraph`](super::LoadedGraph) says which values it was loaded with.

use std::collections::BTreeMap;

/// Values for a graph file's parameters, by name. Given to
/// [`load_file_with`](super::load_file_with); a name the file does not declare is an
/// error there, so a misspelt parameter never goes unnoticed. A
/// [`LoadedGraph`](super::LoadedGraph)'s [`params`](super::LoadedGraph::params) holds
/// every parameter its file declares, each with the value it took.
#[derive(Clone, Debug, Default, PartialEq, Eq, Hash)]
pub struct GraphParams(pub(super) BTreeMap<String, u32>);

impl GraphParams {
    /// No values: every parameter takes its default.
    pub fn new() -> Self {
        Self::default()
    }

    /// These values with `name` set to `value`.
    pub fn with(mut self, name: impl Into<String>, value: u32) -> Self {
        self.0.insert(name.into(), value);
        self
    }

    /// The value given for `name`, if any.
    pub fn get(&self, name: &str) -> Option<u32> {
        self.0.get(name).copied()
    }

    /// These values, with every value of `other` replacing the one of its name.
    pub fn overridden_by(&self, other: &GraphParams) -> GraphParams {
        other.iter().fold(self.clone(), |values, (name, value)| {
            values.with(name, value)
        })
    }

    /// The values, sorted by name.
    pub fn iter(&self) -> impl Iterator<Item = (&str, u32)> {
        self.0.iter().map(|(name, value)| (name.as_str(), *value))
    }
}
