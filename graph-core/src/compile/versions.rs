//! Who produces and who consumes each version of each resource: the edges every later
//! phase walks.

use std::collections::HashMap;

use crate::graph::Graph;
use crate::handle::{PassId, ResourceId};

pub(super) type Version = (ResourceId, u32);

#[derive(Default)]
pub(super) struct Versions {
    /// The pass that produced each version.
    pub writer: HashMap<Version, PassId>,
    /// The passes that depend on each version's contents, in declaration order.
    pub readers: HashMap<Version, Vec<PassId>>,
    /// The pass that writes over each version (at most one in a valid graph).
    pub overwriter: HashMap<Version, PassId>,
    /// The passes that access each resource, in declaration order.
    pub users: Vec<Vec<PassId>>,
}

impl Versions {
    pub fn index(graph: &Graph) -> Self {
        let mut v = Self {
            users: vec![Vec::new(); graph.resources.len()],
            ..Self::default()
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
                    let readers = v.readers.entry(incoming).or_default();
                    if readers.last() != Some(&id) {
                        readers.push(id);
                    }
                }
                if let Some(written) = access.written {
                    v.writer.insert((access.resource, written), id);
                    v.overwriter.entry(incoming).or_insert(id);
                }
            }
        }
        v
    }

    pub fn readers(&self, version: Version) -> &[PassId] {
        self.readers.get(&version).map(Vec::as_slice).unwrap_or(&[])
    }

    /// The last version of a resource: the one roots keep.
    pub fn final_version(graph: &Graph, resource: ResourceId) -> u32 {
        graph.resources[resource.index()].versions - 1
    }
}
