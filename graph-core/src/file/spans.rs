//! Where things are in a loaded graph file, kept after its text is gone, so compile
//! errors (which know pass and resource names only) can be placed in the file.

use std::collections::HashMap;

use super::error::{ErrorKind, FileError, Location};
use super::schema::GraphFile;
use super::source::Source;
use crate::error::GraphError;
use crate::position::Position;

#[derive(Debug, Clone)]
pub(crate) struct Spans {
    start: Location,
    passes: HashMap<String, Location>,
    resources: HashMap<String, Location>,
    /// (pass, declared resource) -> the first slot of the pass that names a version of it.
    uses: HashMap<(String, String), Location>,
}

impl Spans {
    pub fn new(source: &Source<'_>, file: &GraphFile<'_>) -> Self {
        let mut passes = HashMap::new();
        for pass in &file.passes {
            passes
                .entry(pass.name.as_str().to_owned())
                .or_insert_with(|| source.locate(&pass.name));
        }
        let mut resources = HashMap::new();
        for (name, _) in &file.resources.0 {
            resources
                .entry(name.as_str().to_owned())
                .or_insert_with(|| source.locate(name));
        }
        Spans {
            start: source.location(Position::START),
            passes,
            resources,
            uses: HashMap::new(),
        }
    }

    /// Records that `pass` names a version of `resource` at `at`.
    pub fn record_use(&mut self, pass: &str, resource: &str, at: Location) {
        self.uses
            .entry((pass.to_owned(), resource.to_owned()))
            .or_insert(at);
    }

    /// Places a graph error: at the pass's slot naming the resource, else at the pass,
    /// else at the resource's declaration, else at the start of the file.
    pub fn locate(&self, error: GraphError) -> FileError {
        let pass = error.pass().map(str::to_owned);
        let resource = error.resource().map(str::to_owned);
        let location = pass
            .clone()
            .zip(resource.clone())
            .and_then(|key| self.uses.get(&key))
            .or_else(|| pass.and_then(|p| self.passes.get(&p)))
            .or_else(|| resource.and_then(|r| self.resources.get(&r)))
            .unwrap_or(&self.start)
            .clone();
        FileError {
            location,
            kind: ErrorKind::Graph(error),
        }
    }
}
