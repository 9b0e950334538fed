//! Who produces and who consumes each version of each resource: the edges every later
//! phase walks.
//!
//! Versions count up from 0 per resource, so they are stored densely: one table with a
//! row per version, each resource's rows contiguous. Every lookup is an index, not a hash.

use crate::graph::Graph;
use crate::handle::{PassId, ResourceId};

pub(super) type Version = (ResourceId, u32);

#[derive(Default, Clone)]
struct Row {
    /// The pass that produced the version.
    writer: Option<PassId>,
    /// The passes that depend on the version's contents, in declaration order.
    readers: Vec<PassId>,
    /// The pass that writes over the version (at most one in a valid graph).
    overwriter: Option<PassId>,
}

pub(super) struct Versions {
    /// Where each resource's rows start in `rows`, plus the end of the last one.
    start: Vec<usize>,
    rows: Vec<Row>,
    /// The passes that access each resource, in declaration order.
    pub users: Vec<Vec<PassId>>,
    /// The last version of each resource a pass writes (0 when none does).
    finals: Vec<u32>,
}

impl Versions {
    pub fn index(graph: &Graph) -> Self {
        let mut start = Vec::with_capacity(graph.resources.len() + 1);
        start.push(0);
        for resource in &graph.resources {
            start.push(start[start.len() - 1] + resource.versions as usize);
        }
        let mut v = Self {
            rows: vec![Row::default(); start[start.len() - 1]],
            start,
            users: vec![Vec::new(); graph.resources.len()],
            finals: vec![0; graph.resources.len()],
        };
        for (i, pass) in graph.passes.iter().enumerate() {
            let id = PassId(i as u32);
            for access in &pass.accesses {
                let users = &mut v.users[access.resource.index()];
                if users.last() != Some(&id) {
                    users.push(id);
                }
                let incoming = (access.resource, access.version);
                if access.role.reads() {
                    if let Some(row) = v.row_mut(incoming) {
                        if row.readers.last() != Some(&id) {
                            row.readers.push(id);
                        }
                    }
                }
                if let Some(written) = access.written {
                    if let Some(row) = v.row_mut((access.resource, written)) {
                        row.writer = Some(id);
                        let last = &mut v.finals[access.resource.index()];
                        *last = (*last).max(written);
                    }
                    if let Some(row) = v.row_mut(incoming) {
                        row.overwriter.get_or_insert(id);
                    }
                }
            }
        }
        v
    }

    /// The row of a version, if the graph made it. The builder hands out only versions it
    /// made, so a miss is a foreign handle, which validation reports.
    fn row(&self, (resource, version): Version) -> Option<&Row> {
        let r = resource.index();
        let (&first, &end) = (self.start.get(r)?, self.start.get(r + 1)?);
        let i = first + version as usize;
        (i < end).then(|| &self.rows[i])
    }

    fn row_mut(&mut self, (resource, version): Version) -> Option<&mut Row> {
        let r = resource.index();
        let (&first, &end) = (self.start.get(r)?, self.start.get(r + 1)?);
        let i = first + version as usize;
        (i < end).then(|| &mut self.rows[i])
    }

    pub fn writer(&self, version: Version) -> Option<PassId> {
        self.row(version).and_then(|row| row.writer)
    }

    pub fn readers(&self, version: Version) -> &[PassId] {
        self.row(version).map_or(&[], |row| row.readers.as_slice())
    }

    pub fn overwriter(&self, version: Version) -> Option<PassId> {
        self.row(version).and_then(|row| row.overwriter)
    }

    /// The last version of a resource a pass writes: the one roots keep. In a graph
    /// without dropped passes that is the last version handed out; with them, versions
    /// only dropped passes wrote have no writer and are passed over.
    pub fn final_version(&self, resource: ResourceId) -> u32 {
        self.finals[resource.index()]
    }
}
