//! Physical plan: graph-owned resources with the same shape and usages share one texture
//! or buffer when their lifetimes do not overlap. wgpu has no placed resources, so
//! sharing by descriptor is the memory saving available (see the README).

use std::collections::HashMap;
use std::hash::Hash;

use wgpu_types::{BufferUsages, TextureUsages};

use crate::graph::Graph;
use crate::plan::{PhysicalBuffer, PhysicalTexture, TextureShape};
use crate::resource::Origin;

use super::usage::Usages;

pub(super) struct Physical {
    pub textures: Vec<PhysicalTexture>,
    pub buffers: Vec<PhysicalBuffer>,
    /// For each resource, its index into `textures` or `buffers`.
    pub assignment: Vec<Option<usize>>,
}

/// One physical object being filled, and when it is next free.
struct Slot {
    index: usize,
    free_after: usize,
    /// Exported contents must survive the frame: nothing may move in after them.
    sealed: bool,
}

pub(super) fn plan(
    graph: &Graph,
    shapes: &[Option<TextureShape>],
    lifetimes: &[Option<(usize, usize)>],
    usages: &Usages,
) -> Physical {
    let mut by_start: Vec<usize> = (0..graph.resources.len())
        .filter(|&r| graph.resources[r].origin == Origin::Transient && lifetimes[r].is_some())
        .collect();
    by_start.sort_by_key(|&r| (lifetimes[r].map(|l| l.0), r));

    let mut texture_slots: Slots<(TextureShape, TextureUsages)> = HashMap::new();
    let mut buffer_slots: Slots<(u64, BufferUsages)> = HashMap::new();
    let mut out = Physical {
        textures: Vec::new(),
        buffers: Vec::new(),
        assignment: vec![None; graph.resources.len()],
    };
    for r in by_start {
        let resource = &graph.resources[r];
        let (first, last) = lifetimes[r].unwrap_or_default();
        let id = crate::handle::ResourceId(r as u32);
        let slot = match (shapes[r], resource.buffer()) {
            (Some(shape), _) => {
                let key = (shape, usages.texture[r]);
                let fresh = out.textures.len();
                let slot = assign(
                    &mut texture_slots,
                    key,
                    fresh,
                    (first, last),
                    resource.exported,
                );
                if slot == out.textures.len() {
                    out.textures.push(PhysicalTexture {
                        shape,
                        usage: key.1,
                        bytes: shape_bytes(&shape),
                        holds: Vec::new(),
                    });
                }
                out.textures[slot].holds.push(id);
                slot
            }
            (None, Some(desc)) => {
                let key = (desc.size, usages.buffer[r]);
                let fresh = out.buffers.len();
                let slot = assign(
                    &mut buffer_slots,
                    key,
                    fresh,
                    (first, last),
                    resource.exported,
                );
                if slot == out.buffers.len() {
                    out.buffers.push(PhysicalBuffer {
                        size: desc.size,
                        usage: key.1,
                        holds: Vec::new(),
                    });
                }
                out.buffers[slot].holds.push(id);
                slot
            }
            (None, None) => continue,
        };
        out.assignment[r] = Some(slot);
    }
    out
}

/// Free-lists of physical objects by key.
type Slots<K> = HashMap<K, Vec<Slot>>;

/// The index of the first physical object with this key that is free before `first`, or
/// `fresh` (the next new index) when none is.
fn assign<K: Hash + Eq>(
    slots: &mut Slots<K>,
    key: K,
    fresh: usize,
    (first, last): (usize, usize),
    exported: bool,
) -> usize {
    let list = slots.entry(key).or_default();
    match list.iter_mut().find(|s| !s.sealed && s.free_after < first) {
        Some(slot) => {
            slot.free_after = last;
            slot.sealed = exported;
            slot.index
        }
        None => {
            list.push(Slot {
                index: fresh,
                free_after: last,
                sealed: exported,
            });
            fresh
        }
    }
}

pub(super) fn shape_bytes(shape: &TextureShape) -> u64 {
    crate::resource::TextureDesc {
        format: shape.format,
        size: crate::resource::Size::Absolute(shape.width, shape.height),
        samples: shape.samples,
        mips: shape.mips,
        layers: shape.layers,
    }
    .bytes((shape.width, shape.height))
}
