//! Slots: a pass's named connections to resources, as the graph file lists them in
//! `inputs` and `outputs`. Plugins take their handles by slot name.

use std::collections::HashMap;
use std::path::Path;

use super::any_handle::AnyHandle;
use super::plugin_error::PluginError;
use super::references::{ReferenceError, References};
use super::schema::PassDecl;
use crate::access::ColorLoad;
use crate::bounded_read;
use crate::handle::{Handle, Kind, ResourceKind, Texture};
use crate::shader::{Shader, ShaderError};

/// The slots of the pass being set up. A slot only in `inputs` is read; a slot in
/// `outputs` is written, and when it is also in `inputs` it modifies the version it
/// reads (the written version gets the name from `outputs`). Every slot must be taken
/// exactly as listed, or loading fails naming it.
pub struct Slots<'s> {
    /// Output slots in file order (their color-attachment order), then input-only slots.
    slots: Vec<Slot<'s>>,
    /// The folder of the graph file the pass is written in, which its file paths are
    /// relative to, and where they may lead.
    dir: &'s Path,
    references: &'s References,
}

struct Slot<'s> {
    name: &'s str,
    /// The version read, when the slot is an input.
    input: Option<&'s str>,
    /// The version written, when the slot is an output.
    output: Option<&'s str>,
    /// What the plugin gets: the version read, or version 0 of a freshly written resource.
    handle: AnyHandle,
    /// The file marks the read (or the fresh write) `optional`.
    optional: bool,
    used: bool,
    written: Option<AnyHandle>,
}

/// An output slot's resource, as the plugin writes it.
#[derive(Copy, Clone, Debug)]
pub struct Target<K: ResourceKind> {
    /// The version the slot holds before the pass: give it to the access verb that writes.
    pub handle: Handle<K>,
    /// The slot is also an input: the pass draws over (or updates) the version it reads,
    /// rather than replacing the contents.
    pub modifies: bool,
}

impl Target<Texture> {
    /// Load what is there when modifying, else clear to `clear`.
    pub fn color_load(&self, clear: [f64; 4]) -> ColorLoad {
        if self.modifies {
            ColorLoad::Load
        } else {
            ColorLoad::Clear(clear)
        }
    }
}

/// One slot as the caller lists it: its name, the name of the version it reads (inputs),
/// the name of the version it writes (outputs), and the handle the plugin gets (the
/// version read, else the resource written).
pub(crate) struct SlotPart<'s> {
    pub name: &'s str,
    pub input: Option<&'s str>,
    pub output: Option<&'s str>,
    pub handle: AnyHandle,
    /// The read is optional (a file's `optional:`).
    pub optional: bool,
}

/// What a pass's setup produced, for the loader.
pub(crate) struct Finished<'s> {
    /// Slot names, output names and the handles written under them.
    pub written: Vec<(&'s str, &'s str, AnyHandle)>,
    /// Slots the plugin never took, with the name each holds.
    pub unused: Vec<(&'s str, &'s str)>,
    /// The handles of the optional slots the plugin took: the loader marks the pass's
    /// reads (or fresh writes) of them optional.
    pub optional: Vec<AnyHandle>,
    /// Every slot the plugin took, with the version it names: the one written for an
    /// output, else the one read.
    pub taken: Vec<(&'s str, AnyHandle)>,
}

impl<'s> Slots<'s> {
    /// The slots of `decl`, with handles from `handles` by the name each slot reads, or
    /// from `declared` (version 0 of each declared resource) by the name a slot only
    /// writes: alternatives writing one resource under exclusive conditions all write
    /// over its first version. `None` when a name has no handle, which happens only when
    /// the pass writing it failed and was reported already.
    pub(crate) fn new(
        decl: &'s PassDecl<'_>,
        handles: &HashMap<&str, AnyHandle>,
        declared: &HashMap<&str, AnyHandle>,
        (dir, references): (&'s Path, &'s References),
    ) -> Option<Self> {
        let outputs = decl.outputs.0.iter().map(|(slot, out)| {
            let input = decl.input(slot.as_str()).map(|n| n.as_str());
            (slot.as_str(), input, Some(out.as_str()))
        });
        let inputs = decl
            .inputs
            .0
            .iter()
            .filter(|(slot, _)| decl.output(slot.as_str()).is_none())
            .map(|(slot, name)| (slot.as_str(), Some(name.as_str()), None));
        let parts = outputs
            .chain(inputs)
            .map(|(name, input, output)| {
                let handle = match input {
                    Some(read) => *handles.get(read)?,
                    None => *declared.get(output?)?,
                };
                Some(SlotPart {
                    name,
                    input,
                    output,
                    handle,
                    optional: decl.optional.iter().any(|o| o.as_str() == name),
                })
            })
            .collect::<Option<Vec<_>>>()?;
        Some(Self::from_parts(parts, dir, references))
    }

    /// Slots from their parts, outputs first and in attachment order.
    pub(crate) fn from_parts(
        parts: Vec<SlotPart<'s>>,
        dir: &'s Path,
        references: &'s References,
    ) -> Self {
        let slots = parts
            .into_iter()
            .map(|p| Slot {
                name: p.name,
                input: p.input,
                output: p.output,
                handle: p.handle,
                optional: p.optional,
                used: false,
                written: None,
            })
            .collect();
        Slots {
            slots,
            dir,
            references,
        }
    }

    /// The handle of an input-only slot.
    pub fn input<K: ResourceKind>(&mut self, slot: &str) -> Result<Handle<K>, PluginError> {
        let s = self.find(slot, "inputs")?;
        if let Some(output) = s.output {
            return Err(PluginError::NotAnInput {
                slot: slot.to_owned(),
                resource: output.to_owned(),
            });
        }
        s.used = true;
        s.typed()
    }

    /// Writes an output slot: `write` declares the access on the pass builder and returns
    /// the handle the builder gave back, which becomes the slot's output name.
    pub fn write<K: ResourceKind>(
        &mut self,
        slot: &str,
        write: impl FnOnce(Target<K>) -> Handle<K>,
    ) -> Result<Handle<K>, PluginError> {
        let s = self.find(slot, "outputs")?;
        if s.output.is_none() {
            return Err(PluginError::NotAnOutput {
                slot: slot.to_owned(),
                resource: s.shown().to_owned(),
            });
        }
        let target = Target {
            handle: s.typed()?,
            modifies: s.input.is_some(),
        };
        s.used = true;
        let written = write(target);
        s.written = Some(written.into());
        Ok(written)
    }

    /// The kind of resource a slot holds, if the file lists the slot.
    pub fn kind(&self, slot: &str) -> Option<Kind> {
        self.get(slot).map(|s| s.handle.kind())
    }

    /// Whether the file marks the slot `optional` (an input-only or an output-only slot):
    /// where a condition drops what it reads (or the resource it writes), the compile
    /// drops the access rather than failing
    /// ([`PassBuilder::optional`](crate::PassBuilder::optional), which the loader calls).
    /// The plugin then prepares to run without it, asking `FrameResources::has` while
    /// recording, before it builds what binds or attaches the slot.
    pub fn optional(&self, slot: &str) -> bool {
        self.get(slot).is_some_and(|s| s.optional)
    }

    /// Whether the file lists the slot in `outputs`.
    pub fn is_output(&self, slot: &str) -> bool {
        self.get(slot).is_some_and(|s| s.output.is_some())
    }

    /// Whether the file lists the slot in both `inputs` and `outputs`: the pass draws over
    /// (or updates) the version it reads.
    pub fn modifies(&self, slot: &str) -> bool {
        self.get(slot)
            .is_some_and(|s| s.input.is_some() && s.output.is_some())
    }

    /// The output slots, in file order.
    pub fn outputs(&self) -> Vec<&'s str> {
        self.slots
            .iter()
            .filter(|s| s.output.is_some())
            .map(|s| s.name)
            .collect()
    }

    /// The file's name for what a slot holds: the name written for an output, else the
    /// name read. For messages.
    pub fn resource(&self, slot: &str) -> Option<&'s str> {
        self.get(slot).map(|s| s.shown())
    }

    /// The WGSL shader the parameters name, relative to the graph file's folder: read (only
    /// inside the folders graph files may reach, see [`Registry`](super::Registry)) and
    /// validated by naga. Messages name it by that path, `..` folded away where it can be.
    pub fn shader(&self, reference: &str) -> Result<Shader, PluginError> {
        let max = bounded_read::MAX_SHADER_BYTES;
        match self.references.read(self.dir, reference, max) {
            Ok(named) => Ok(Shader::parse(named.path.display().to_string(), named.text)?),
            Err(ReferenceError::Refused(reason)) => Err(PluginError::Reference {
                what: "shader",
                reference: reference.to_owned(),
                reason,
            }),
            Err(ReferenceError::Unreadable { path, reason }) => Err(ShaderError::Unreadable {
                path: path.display().to_string(),
                reason: reason.to_string(),
            }
            .into()),
        }
    }

    pub(crate) fn finish(self) -> Finished<'s> {
        let mut finished = Finished {
            written: Vec::new(),
            unused: Vec::new(),
            optional: Vec::new(),
            taken: Vec::new(),
        };
        for s in self.slots {
            if s.used && s.optional {
                finished.optional.push(s.handle);
            }
            if s.used {
                finished.taken.push((s.name, s.written.unwrap_or(s.handle)));
            }
            match (s.used, s.output, s.written) {
                (false, _, _) => finished.unused.push((s.name, s.shown())),
                (true, Some(output), Some(handle)) => {
                    finished.written.push((s.name, output, handle))
                }
                (true, _, _) => {}
            }
        }
        finished
    }

    fn get(&self, slot: &str) -> Option<&Slot<'s>> {
        self.slots.iter().find(|s| s.name == slot)
    }

    fn find(&mut self, slot: &str, side: &'static str) -> Result<&mut Slot<'s>, PluginError> {
        self.slots
            .iter_mut()
            .find(|s| s.name == slot)
            .ok_or_else(|| PluginError::MissingSlot {
                slot: slot.to_owned(),
                side,
            })
    }
}

impl<'s> Slot<'s> {
    fn shown(&self) -> &'s str {
        self.output.or(self.input).unwrap_or(self.name)
    }

    fn typed<K: ResourceKind>(&self) -> Result<Handle<K>, PluginError> {
        self.handle.typed().ok_or_else(|| PluginError::SlotKind {
            slot: self.name.to_owned(),
            resource: self.shown().to_owned(),
            found: kind_name(self.handle.kind()),
            expected: kind_name(K::KIND),
        })
    }
}

fn kind_name(kind: Kind) -> &'static str {
    match kind {
        Kind::Texture => "texture",
        Kind::Buffer => "buffer",
    }
}
