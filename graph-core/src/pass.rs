//! Declared passes: a name, a kind, the accesses it declared and the callback that records it.

use serde::Serialize;

use crate::access::Access;
use crate::condition::Condition;

/// What kind of GPU work a pass records. The executor begins the matching wgpu pass.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum PassKind {
    /// A render pass: the executor begins it with the attachments the pass declared and
    /// the load/store operations the compiler inferred.
    Render,
    /// A compute pass.
    Compute,
    /// Copies and other encoder-level commands.
    Transfer,
}

impl std::fmt::Display for PassKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            PassKind::Render => "render",
            PassKind::Compute => "compute",
            PassKind::Transfer => "transfer",
        })
    }
}

/// Defined here, beside the kinds, so that recording does not import the pass model.
#[cfg(feature = "gpu")]
impl crate::record::Record {
    /// The kind of pass whose commands the callback records.
    pub fn kind(&self) -> PassKind {
        match self {
            Self::Render(_) => PassKind::Render,
            Self::Compute(_) => PassKind::Compute,
            Self::Transfer(_) => PassKind::Transfer,
        }
    }
}

/// What a compute pass's entry point asks of the device: checked against the profile's
/// compute limits when compiling, so a shader too big for a device is a graph error
/// naming the pass, not a pipeline-creation failure on the first frame.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct Workgroup {
    /// The entry point, for messages.
    pub entry: String,
    /// `@workgroup_size`.
    pub size: [u32; 3],
    /// Bytes of `var<workgroup>` memory, as WebGPU counts them.
    pub memory_bytes: u32,
}

/// A pass as declared.
pub struct PassNode {
    /// The pass's name, unique in its graph by convention: messages, plans and timings
    /// name passes by it.
    pub name: String,
    /// The kind of wgpu pass the executor begins for it.
    pub kind: PassKind,
    /// Every access the pass declared, in declaration order.
    pub accesses: Vec<Access>,
    /// Kept even when nothing reads what it writes (e.g. it writes outside the graph).
    pub side_effect: bool,
    /// The pass runs only where this holds for the compiled features.
    pub condition: Option<Condition>,
    /// Why the pass is left out of every plan, when its plugin found at setup that it
    /// has nothing to do: compiled as if its condition were false.
    pub omitted: Option<String>,
    /// A compute pass's workgroup shape and memory for each entry point it dispatches,
    /// in the order its plugin declared them.
    pub workgroups: Vec<Workgroup>,
    /// Where the pass was written, when not in the graph's own file: the part it came
    /// from and where the graph uses it. `explain` shows it.
    pub origin: Option<String>,
    #[cfg(feature = "gpu")]
    pub(crate) record: Option<crate::record::Record>,
}

/// `(resource, version)` pairs.
pub type VersionList = Vec<(crate::handle::ResourceId, u32)>;

impl PassNode {
    /// The versions the pass depends on and the versions it produces.
    pub fn versions(&self) -> (VersionList, VersionList) {
        let reads = self
            .accesses
            .iter()
            .filter_map(|a| a.read_version().map(|v| (a.resource, v)))
            .collect();
        let writes = self
            .accesses
            .iter()
            .filter_map(|a| a.written.map(|v| (a.resource, v)))
            .collect();
        (reads, writes)
    }

    pub(crate) fn new(name: String, kind: PassKind) -> Self {
        Self {
            name,
            kind,
            accesses: Vec::new(),
            side_effect: false,
            condition: None,
            omitted: None,
            workgroups: Vec::new(),
            origin: None,
            #[cfg(feature = "gpu")]
            record: None,
        }
    }

    /// The pass as declared, without its record callback: what compile phases read.
    pub(crate) fn declaration(&self) -> Self {
        Self {
            accesses: self.accesses.clone(),
            side_effect: self.side_effect,
            condition: self.condition.clone(),
            omitted: self.omitted.clone(),
            workgroups: self.workgroups.clone(),
            origin: self.origin.clone(),
            ..Self::new(self.name.clone(), self.kind)
        }
    }
}
